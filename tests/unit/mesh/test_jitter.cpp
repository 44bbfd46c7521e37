// jitter_interior_nodes: interior nodes only, bounded moves, reproducible from the seed.
#include <doctest/doctest.h>

#include "core/error.hpp"
#include "mesh/jitter.hpp"

using namespace quadapt;

TEST_CASE("jitter: interior nodes move within fraction * shortest edge, boundary stays, area kept, seed reproduces") {
  const Mesh start = make_structured_quads(8, 8);  // 81 nodes, 49 interior, edges 1/8
  Mesh a = start, b = start, c = start;
  const int moved = jitter_interior_nodes(a, {0.3, 7});
  CHECK(moved == 49);
  jitter_interior_nodes(b, {0.3, 7});
  jitter_interior_nodes(c, {0.3, 8});
  int on_boundary = 0, changed = 0;
  double largest = 0;
  for (int i = 0; i < start.num_nodes(); ++i) {
    const Vec2& p = start.nodes[i];
    const bool boundary = p.x() == 0 || p.x() == 1 || p.y() == 0 || p.y() == 1;
    const double d = (a.nodes[i] - p).norm();
    if (boundary) {
      ++on_boundary;
      CHECK(d == 0.0);
    } else if (d > 0) {
      ++changed;
    }
    largest = std::max(largest, d);
    CHECK(a.nodes[i] == b.nodes[i]);  // same seed: the same bits
  }
  CHECK(on_boundary == 32);
  CHECK(changed == 49);
  CHECK(largest <= 0.3 / 8 + 1e-15);
  CHECK(largest > 0.5 * 0.3 / 8);  // 49 uniform draws in the disk: one beyond half the radius
  CHECK(total_area(a) == doctest::Approx(1.0).epsilon(1e-14));
  bool differs = false;
  for (int i = 0; i < start.num_nodes(); ++i) differs |= a.nodes[i] != c.nodes[i];
  CHECK(differs);
  CHECK(a.cells.size() == start.cells.size());
  CHECK(a.boundary.size() == start.boundary.size());
}

TEST_CASE("jitter: a fraction outside (0, 0.45] and a curved mesh are refused, the mesh untouched") {
  Mesh m = make_structured_quads(2, 2);
  const Mesh before = m;
  CHECK_THROWS_AS(jitter_interior_nodes(m, {0.0, 1}, "m.msh"), InputError);
  CHECK_THROWS_WITH(jitter_interior_nodes(m, {0.5, 1}, "m.msh"), doctest::Contains("m.msh: jitter fraction"));
  m.curved.order = 2;
  m.curved.points.assign(static_cast<size_t>(m.num_cells()) * 9, Vec2(0, 0));
  CHECK_THROWS_WITH(jitter_interior_nodes(m, {0.2, 1}, "m.msh"), doctest::Contains("curved"));
  for (int i = 0; i < m.num_nodes(); ++i) CHECK(m.nodes[i] == before.nodes[i]);
}
