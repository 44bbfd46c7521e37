#include <doctest/doctest.h>

#include "mesh/mesh.hpp"
#include "mesh/topology.hpp"

using namespace quadapt;

TEST_CASE("structured grid: face counts, normals and areas") {
  Mesh m = make_structured_quads(3, 2);
  CHECK(m.num_cells() == 6);
  CHECK(total_area(m) == doctest::Approx(1.0).epsilon(1e-14));
  Topology t = build_topology(m);
  // interior faces: 2*2 vertical + 3*1 horizontal = 7; boundary: 2*3 + 2*2 = 10
  int interior = 0, boundary = 0;
  for (const auto& f : t.faces) (f.is_boundary() ? boundary : interior)++;
  CHECK(interior == 7);
  CHECK(boundary == 10);
  for (const auto& f : t.faces) {
    CHECK(f.is_conforming());
    if (f.is_boundary()) CHECK(f.group >= 0);
    // normal points out of cell 0: away from its centroid
    Vec2 mid = 0.5 * (f.a + f.b);
    CHECK((mid - cell_centroid(m, f.cell[0])).dot(f.normal) > 0);
  }
}

TEST_CASE("hanging node: a coarse cell beside two fine cells") {
  // Coarse cell [0,1]x[0,1], fine cells [1,1.5]x[0,0.5] and [1,1.5]x[0.5,1]... as 2:1 faces.
  Mesh m;
  m.nodes = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {1, 0.5}, {1.5, 0}, {1.5, 0.5}, {1.5, 1}};
  m.cells = {Cell{{0, 1, 2, 3}, 4}, Cell{{1, 5, 6, 4}, 4}, Cell{{4, 6, 7, 2}, 4}};
  Topology t = build_topology(m);
  int nonconf = 0;
  for (const auto& f : t.faces)
    if (!f.is_boundary() && !f.is_conforming()) {
      ++nonconf;
      CHECK(f.cell[0] == 0);
      CHECK(f.length == doctest::Approx(0.5));
      CHECK(std::abs(f.s_b[0] - f.s_a[0]) == doctest::Approx(0.5));
    }
  CHECK(nonconf == 2);
  CHECK(t.neighbours(0).size() == 2);
  CHECK(t.cell_faces[0].size() == 5);
}
