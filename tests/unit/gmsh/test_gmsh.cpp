// lib/gmsh: the SDK adapter (sessions, option guard, Blossom-Quad recombination).
#include <doctest/doctest.h>
#include <algorithm>
#include <gmsh.h>

#include "core/error.hpp"
#include "gmsh/geometry.hpp"
#include "gmsh/gmsh_recombine.hpp"
#include "gmsh/session.hpp"
#include "mesh/boundary.hpp"

using namespace quadapt;

TEST_CASE("GmshOptionGuard restores the caller's options, also after an error") {
  GmshSession session;
  gmsh::option::setNumber("Mesh.Smoothing", 7);
  {
    GmshOptionGuard g({{"Mesh.Smoothing", 2}});
    double v = 0;
    gmsh::option::getNumber("Mesh.Smoothing", v);
    CHECK(v == 2);
  }
  double v = 0;
  gmsh::option::getNumber("Mesh.Smoothing", v);
  CHECK(v == 7);
  CHECK_THROWS_AS(gmsh_call("test", [] {
                    GmshOptionGuard g({{"Mesh.Smoothing", 3}});
                    throw std::string("failure inside Gmsh");
                  }),
                  ExternalError);
  gmsh::option::getNumber("Mesh.Smoothing", v);
  CHECK(v == 7);
}

namespace {
// The unit square as two triangles.
Mesh two_triangles() {
  Mesh tri;
  tri.nodes = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  Cell a, b;
  a.nv = b.nv = 3;
  a.v = {0, 1, 2, -1};
  b.v = {0, 2, 3, -1};
  tri.cells = {a, b};
  return tri;
}
}  // namespace

TEST_CASE("gmsh_recombine: two triangles of the unit square become one quad, nodes kept") {
  const Mesh tri = two_triangles();
  const std::vector<std::vector<int>> loops = {{0, 1, 2, 3}};
  const std::vector<char> on_boundary(4, 1);
  GmshRecombined r = gmsh_recombine(tri, loops, on_boundary, {});
  REQUIRE(r.cells.size() == 1);
  CHECK(r.cells[0].nv == 4);
  CHECK(r.nodes.size() == 4);
  Mesh q;
  q.nodes = r.nodes;
  q.cells = r.cells;
  CHECK(free_edges(q).size() == 4);
  CHECK(cell_area(q, 0) == doctest::Approx(1));
}

TEST_CASE("a caller's own Gmsh: quadapt borrows it and leaves its models, current model and options") {
  // open_geometry and Blossom finalized a Gmsh the caller had initialised: its models, current
  // model and options were gone (a library user's review, session 38)
  gmsh::initialize(0, nullptr, false);
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::model::add("mine");
  gmsh::model::geo::addPoint(0.5, 0.25, 0);
  gmsh::model::geo::synchronize();
  gmsh::option::setNumber("Mesh.MeshSizeMax", 0.123);
  gmsh::option::setNumber("General.AbortOnError", 2);
  std::vector<std::string> before;
  gmsh::model::list(before);  // Gmsh's first, unnamed model and "mine"
  {
    const auto g = open_geometry(std::string(QUADAPT_SOURCE_DIR) + "/examples/geometry/cylinder.geo");
    CHECK(g->num_curves() > 0);
    CHECK(gmsh_recombine(two_triangles(), {{0, 1, 2, 3}}, std::vector<char>(4, 1), {}).cells.size() == 1);
  }
  std::vector<std::string> names;
  gmsh::model::list(names);
  CHECK(names == before);
  CHECK(std::count(names.begin(), names.end(), "mine") == 1);
  std::string current;
  gmsh::model::getCurrent(current);
  CHECK(current == "mine");
  gmsh::vectorpair points;
  gmsh::model::getEntities(points, 0);
  CHECK(points.size() == 1);
  double v = 0;
  gmsh::option::getNumber("Mesh.MeshSizeMax", v);
  CHECK(v == 0.123);
  gmsh::option::getNumber("General.AbortOnError", v);
  CHECK(v == 2);
  gmsh::finalize();
  // and on its own again afterwards (its own session, initialised and finalized)
  const auto g = open_geometry(std::string(QUADAPT_SOURCE_DIR) + "/examples/geometry/cylinder.geo");
  CHECK(g->num_curves() > 0);
}
