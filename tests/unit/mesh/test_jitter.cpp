// jitter_interior_nodes: interior nodes only, bounded moves, reproducible from the seed.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "../dg/dg_test_meshes.hpp"
#include "core/error.hpp"
#include "mesh/jitter.hpp"

using namespace quadapt;

namespace {
// The smallest corner cross product over every cell, in units of the cell's area: > 0 when no
// cell is inverted or non-convex. (The sum of the signed cell areas is the domain's whatever the
// moves, folded cells included, so "area kept" alone could not fail: a test audit, session 38.)
double worst_corner(const Mesh& m) {
  double w = 1e300;
  for (int c = 0; c < m.num_cells(); ++c) {
    const Cell& k = m.cells[c];
    for (int i = 0; i < k.nv; ++i) {
      const Vec2 a = m.nodes[k.v[(i + k.nv - 1) % k.nv]], o = m.nodes[k.v[i]], b = m.nodes[k.v[(i + 1) % k.nv]];
      const Vec2 e1 = b - o, e2 = a - o;
      w = std::min(w, (e1.x() * e2.y() - e1.y() * e2.x()) / std::abs(cell_area(m, c)));
    }
  }
  return w;
}
// Each node's shortest incident cell edge.
std::vector<double> shortest_edge(const Mesh& m) {
  std::vector<double> h(m.nodes.size(), 1e300);
  for (const Cell& k : m.cells)
    for (int i = 0; i < k.nv; ++i) {
      const int a = k.v[i], b = k.v[(i + 1) % k.nv];
      const double l = (m.nodes[a] - m.nodes[b]).norm();
      h[a] = std::min(h[a], l);
      h[b] = std::min(h[b], l);
    }
  return h;
}
}  // namespace

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
  CHECK(worst_corner(a) > 0);
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

TEST_CASE("jitter: on a graded mesh each node moves within fraction * its own shortest edge; cells stay convex") {
  Mesh start = make_structured_quads(8, 8);
  for (Vec2& p : start.nodes) p = Vec2(p.x() * p.x() * p.x(), p.y());  // x^3: edges 1/512 .. 0.33 across
  const std::vector<double> h = shortest_edge(start);
  Mesh a = start;
  const int moved = jitter_interior_nodes(a, {0.4, 3});
  CHECK(moved == 49);
  double worst = 0, near_wall = 0;  // move / own shortest edge; the largest move of the x <= 1/8 column
  for (int i = 0; i < start.num_nodes(); ++i) {
    const double d = (a.nodes[i] - start.nodes[i]).norm();
    worst = std::max(worst, d / h[i]);
    if (start.nodes[i].x() > 0 && start.nodes[i].x() <= 1.0 / 512 + 1e-15) near_wall = std::max(near_wall, d);
  }
  CHECK(worst <= 0.4 + 1e-12);
  CHECK(worst > 0.2);
  CHECK(near_wall <= 0.4 / 512 + 1e-15);  // a radius from the coarse edges would fold these cells
  CHECK(worst_corner(a) > 0);
}

TEST_CASE("jitter: the hanging nodes of a 2:1 mesh stay on their edges") {
  const Mesh start = dgtest::checkerboard_split(make_structured_quads(4, 4), 4);
  // hanging nodes: the midpoints of an unsplit cell's edges
  std::vector<char> hanging(start.nodes.size(), 0);
  int nh = 0;
  for (const Cell& k : start.cells)
    for (int i = 0; i < k.nv; ++i) {
      const Vec2 mid = 0.5 * (start.nodes[k.v[i]] + start.nodes[k.v[(i + 1) % k.nv]]);
      for (int n = 0; n < start.num_nodes(); ++n)
        if ((start.nodes[n] - mid).norm() < 1e-14 && !hanging[n]) hanging[n] = 1, ++nh;
    }
  REQUIRE(nh > 0);
  Mesh a = start;
  const int moved = jitter_interior_nodes(a, {0.3, 5});
  int hanging_moved = 0, others_moved = 0;
  for (int i = 0; i < start.num_nodes(); ++i) {
    const bool d = a.nodes[i] != start.nodes[i];
    if (hanging[i]) hanging_moved += d;
    else others_moved += d;
  }
  CHECK(hanging_moved == 0);
  CHECK(others_moved == moved);
  CHECK(moved > 0);
  CHECK(worst_corner(a) > 0);
}
