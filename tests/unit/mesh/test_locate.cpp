// CellLocator (mesh/locate.hpp): on a strongly graded mesh, whose thin cells crowd a few buckets
// into sub-grids, the cell found is the one a search of every cell finds — the lowest-numbered
// cell containing x — also for points on shared edges and at shared vertices (ties) — and
// locate_all lists every containing cell.
#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <vector>

#include "mesh/locate.hpp"
#include "mesh/mesh.hpp"

using namespace quadapt;

namespace {

// The locator's own closed point-in-polygon test (edges count as inside), over every cell.
bool inside_closed(const Mesh& m, int c, const Vec2& x) {
  const Cell& cell = m.cells[c];
  bool in = false;
  for (int i = 0, j = cell.nv - 1; i < cell.nv; j = i++) {
    const Vec2& a = m.nodes[cell.v[i]];
    const Vec2& b = m.nodes[cell.v[j]];
    const Vec2 ab = b - a, ax = x - a;
    const double cr = ab.x() * ax.y() - ab.y() * ax.x();
    const double len2 = ab.squaredNorm();
    if (std::abs(cr) <= 1e-14 * len2 && ax.dot(ab) >= 0 && ax.dot(ab) <= len2) return true;
    if ((a.y() > x.y()) != (b.y() > x.y()) && x.x() < a.x() + (x.y() - a.y()) * ab.x() / ab.y()) in = !in;
  }
  return in;
}

int first_containing(const Mesh& m, const Vec2& x) {
  for (int c = 0; c < m.num_cells(); ++c)
    if (inside_closed(m, c, x)) return c;
  return -1;
}

}  // namespace

TEST_CASE("point location: a graded mesh's crowded buckets give the lowest-numbered containing cell") {
  // 40 x 40 cells, y -> y^6 (cells 4e-10 thick at the wall: ~22 rows share the first bucket row),
  // sheared so that the cells are parallelograms
  Mesh m = make_structured_quads(40, 40);
  for (Vec2& p : m.nodes) p = Vec2(p.x() + 0.1 * p.y(), std::pow(p.y(), 6));
  const CellLocator loc(m);
  std::vector<Vec2> xs;
  for (const Vec2& p : m.nodes) xs.push_back(p);  // shared vertices: up to four cells each
  for (const Cell& c : m.cells)
    for (int i = 0; i < c.nv; ++i) {
      xs.push_back(0.5 * (m.nodes[c.v[i]] + m.nodes[c.v[(i + 1) % c.nv]]));  // shared edges
      xs.push_back(0.25 * (m.nodes[c.v[0]] + m.nodes[c.v[1]] + m.nodes[c.v[2]] + m.nodes[c.v[3]]));
    }
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> ux(-0.05, 1.15), uy(0, 1);
  for (int k = 0; k < 4000; ++k) xs.push_back(Vec2(ux(rng), std::pow(uy(rng), 6)));  // dense near the wall
  int found = 0, ties = 0;
  std::vector<int> all, want_all;
  for (const Vec2& x : xs) {
    const int want = first_containing(m, x);
    REQUIRE(loc.locate(x) == want);
    // locate_all: every containing cell, ascending (FrameSampler chooses among them)
    want_all.clear();
    for (int c = 0; c < m.num_cells(); ++c)
      if (inside_closed(m, c, x)) want_all.push_back(c);
    loc.locate_all(x, all);
    REQUIRE(all == want_all);
    if (want < 0) continue;
    ++found;
    ties += want_all.size() > 1;
  }
  CHECK(found > 10000);
  CHECK(ties > 3000);  // the shared vertices and edges were tested
}

TEST_CASE("well_inside: a point in a cell's interior away from its edges lies in that cell only") {
  // the graded, sheared mesh above: wherever well_inside(c, x) holds, locate(x) == c, so a caller
  // may keep c as x moves (quadsmooth's per-node frame cell); on and near edges it does not hold
  Mesh m = make_structured_quads(40, 40);
  for (Vec2& p : m.nodes) p = Vec2(p.x() + 0.1 * p.y(), std::pow(p.y(), 6));
  const CellLocator loc(m);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  int kept = 0;
  for (int c = 0; c < m.num_cells(); ++c) {
    const Cell& cell = m.cells[c];
    const Vec2 a = m.nodes[cell.v[0]], b = m.nodes[cell.v[1]], d = m.nodes[cell.v[3]];
    for (int k = 0; k < 20; ++k) {  // points of the parallelogram, some within rounding of an edge
      double s = u(rng), t = u(rng);
      if (k % 5 == 0) s = 1e-13;
      const Vec2 x = a + s * (b - a) + t * (d - a);
      if (!loc.well_inside(c, x)) continue;
      ++kept;
      REQUIRE(first_containing(m, x) == c);
      for (int o = std::max(0, c - 41); o <= std::min(m.num_cells() - 1, c + 41); ++o)
        if (o != c) REQUIRE_FALSE(loc.well_inside(o, x));
    }
    CHECK_FALSE(loc.well_inside(c, m.nodes[cell.v[0]]));                        // a vertex
    CHECK_FALSE(loc.well_inside(c, 0.5 * (m.nodes[cell.v[0]] + m.nodes[cell.v[1]])));  // an edge
  }
  CHECK(kept > 20000);
  CHECK_FALSE(loc.well_inside(-1, Vec2(0.5, 0.5)));
  CHECK_FALSE(loc.well_inside(m.num_cells(), Vec2(0.5, 0.5)));
}
