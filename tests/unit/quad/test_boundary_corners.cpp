#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>

#include "mesh/geometry.hpp"
#include "mesh/mesh.hpp"
#include "mesh/validate.hpp"
#include "quad/boundary_corners.hpp"

using namespace quadapt;

namespace {
Mesh two_quads(double dip) {
  // A hexagon v, b, r1, r2, c, a split along c-b: v = (1, -dip) on a bent bottom wall a - v - b is
  // touched by Q = (v, b, c, a) only, R = (c, b, r1, r2) is its neighbour across b-c. The angle of
  // Q at v is 180 - 2 atan(dip) degrees.
  Mesh m;
  m.nodes = {Vec2(1, -dip), Vec2(2, 0), Vec2(-0.2, 1), Vec2(0, 0),  // v b c a
             Vec2(2.2, 1), Vec2(1, 1.6)};                           // r1 r2
  Cell q, r;
  q.v = {0, 1, 2, 3};
  r.v = {2, 1, 4, 5};
  m.cells = {q, r};
  return m;
}

std::set<std::pair<int, int>> free_edges(const Mesh& m) {
  std::multiset<std::pair<int, int>> all;
  for (const Cell& c : m.cells)
    for (int k = 0; k < c.nv; ++k)
      all.insert({std::min(c.v[k], c.v[(k + 1) % c.nv]), std::max(c.v[k], c.v[(k + 1) % c.nv])});
  std::set<std::pair<int, int>> once;
  for (const auto& e : all)
    if (all.count(e) == 1) once.insert(e);
  return once;
}

int cells_at(const Mesh& m, int v) {
  return static_cast<int>(std::count_if(m.cells.begin(), m.cells.end(), [&](const Cell& c) {
    return std::find(c.v.begin(), c.v.begin() + c.nv, v) != c.v.begin() + c.nv;
  }));
}

double area(const Mesh& m) {
  double a = 0;
  for (int c = 0; c < m.num_cells(); ++c) a += cell_area(m, c);
  return a;
}
}  // namespace

TEST_CASE("a flat boundary corner in one quad: the quad goes back to two triangles, v gets two cells") {
  Mesh m = two_quads(0.05);  // 174.3 degrees at v
  const auto edges_before = free_edges(m);
  const double area_before = area(m);
  REQUIRE(cells_at(m, 0) == 1);
  const BoundaryCornerStats st = split_flat_boundary_corners(m);
  CHECK(st.flat_vertices == 1);
  CHECK(st.split == 1);
  CHECK(m.num_cells() == 3);
  CHECK(m.num_triangles() == 2);
  CHECK(cells_at(m, 0) == 2);
  CHECK(free_edges(m) == edges_before);  // the boundary, so its groups, is kept
  CHECK(area(m) == doctest::Approx(area_before).epsilon(1e-14));
  for (int c = 0; c < m.num_cells(); ++c) CHECK(cell_shape_problem(m, c).empty());
  // the two angles at v add up to the old one, each below the bound
  double sum = 0;
  for (const Cell& c : m.cells)
    if (std::find(c.v.begin(), c.v.begin() + c.nv, 0) != c.v.begin() + c.nv) {
      const int k = static_cast<int>(std::find(c.v.begin(), c.v.begin() + c.nv, 0) - c.v.begin());
      const Vec2 e1 = m.nodes[c.v[(k + 1) % c.nv]] - m.nodes[0], e0 = m.nodes[c.v[(k + c.nv - 1) % c.nv]] - m.nodes[0];
      const double deg = std::acos(e1.dot(e0) / (e1.norm() * e0.norm())) * 180 / M_PI;
      CHECK(deg < 150);
      sum += deg;
    }
  CHECK(sum == doctest::Approx(180 - 2 * std::atan(0.05) * 180 / M_PI).epsilon(1e-12));
  // idempotent: nothing flat is left
  CHECK(split_flat_boundary_corners(m).flat_vertices == 0);
}

TEST_CASE("a boundary corner below the bound is left alone; a grid has none") {
  Mesh sharp = two_quads(0.6);  // a real corner of the domain: 118 degrees at v
  const Mesh before = sharp;
  CHECK(split_flat_boundary_corners(sharp).flat_vertices == 0);
  REQUIRE(sharp.num_cells() == before.num_cells());
  for (int c = 0; c < sharp.num_cells(); ++c) CHECK(sharp.cells[c].v == before.cells[c].v);
  Mesh grid = make_structured_quads(4, 3);
  const BoundaryCornerStats st = split_flat_boundary_corners(grid);
  CHECK(st.flat_vertices == 0);
  CHECK(grid.num_cells() == 12);
}
