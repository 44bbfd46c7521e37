// lib/gmsh: the SDK adapter (sessions, option guard, Blossom-Quad recombination).
#include <doctest/doctest.h>
#include <gmsh.h>

#include "core/error.hpp"
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

TEST_CASE("gmsh_recombine: two triangles of the unit square become one quad, nodes kept") {
  Mesh tri;
  tri.nodes = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  Cell a, b;
  a.nv = b.nv = 3;
  a.v = {0, 1, 2, -1};
  b.v = {0, 2, 3, -1};
  tri.cells = {a, b};
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
