// Boundary edges lying on other boundary edges: blocks whose shared nodes were not merged.
#include <doctest/doctest.h>

#include <array>
#include <string>

#include "mesh/near_boundary.hpp"
#include "mesh/validate.hpp"

using namespace quadapt;

namespace {
/// The cells of a and b in one mesh, no node merged, no boundary (derived from the free edges).
Mesh side_by_side(const Mesh& a, const Mesh& b) {
  Mesh m;
  m.nodes = a.nodes;
  m.cells = a.cells;
  m.nodes.insert(m.nodes.end(), b.nodes.begin(), b.nodes.end());
  for (Cell c : b.cells) {
    for (int k = 0; k < c.nv; ++k) c.v[k] += a.num_nodes();
    m.cells.push_back(c);
  }
  return m;
}
}  // namespace

TEST_CASE("two unit-square halves 1e-6 apart: one warning naming the count") {
  const Mesh m = side_by_side(make_structured_quads(4, 8, 0, 0.5, 0, 1), make_structured_quads(4, 8, 0.5 + 1e-6, 1, 0, 1));
  validate_mesh(m, "halves.msh");  // valid: a domain with a slit
  const auto pairs = overlapping_edges(m, boundary_free_edges(m));
  REQUIRE(pairs.size() == 8);  // the 8 edges of x = 0.5 against the 8 of x = 0.5 + 1e-6
  for (const EdgeOverlap& p : pairs) CHECK(p.gap == doctest::Approx(1e-6).epsilon(1e-6));
  const auto w = boundary_warnings(m);
  REQUIRE(w.size() == 1);
  INFO(w[0]);
  CHECK(w[0].rfind("16 boundary edges lie on other boundary edges (8 pairs, at most 1.000e-06 apart; first: ", 0) == 0);
  CHECK(w[0].find("Coherence Mesh") != std::string::npos);
  CHECK(w[0].find('\n') == std::string::npos);
  CHECK(boundary_warnings(m) == w);  // deterministic
}

TEST_CASE("the same halves merged, or a 2:1 interface: no warning") {
  CHECK(boundary_warnings(make_structured_quads(8, 8)).empty());
  CHECK(boundary_warnings(make_perturbed_quads(12, 9, 0.3, 7)).empty());
  // a coarse cell beside two fine ones: the hanging node's half-edges are interior faces
  Mesh h;
  h.nodes = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {1, 0.5}, {1.5, 0}, {1.5, 0.5}, {1.5, 1}};
  for (const std::array<int, 4>& v : {std::array<int, 4>{0, 1, 2, 3}, {1, 5, 6, 4}, {4, 6, 7, 2}}) {
    h.cells.emplace_back();
    h.cells.back().v = v;
  }
  validate_mesh(h, "hanging.msh");
  CHECK(boundary_warnings(h).empty());
}

TEST_CASE("a narrow but real channel (gap 5 x the edge length): no warning") {
  // [0,1] x [0,0.475] and [0,1] x [0.525,1], edges of 0.01 along the channel
  const Mesh m = side_by_side(make_structured_quads(100, 4, 0, 1, 0, 0.475), make_structured_quads(100, 4, 0, 1, 0.525, 1));
  CHECK(boundary_warnings(m).empty());
  // the same 1e-5 apart (0.1% of the edge) is the unmerged case
  const Mesh n = side_by_side(make_structured_quads(100, 4, 0, 1, 0, 0.5), make_structured_quads(100, 4, 0, 1, 0.5 + 1e-5, 1));
  CHECK(overlapping_edges(n, boundary_free_edges(n)).size() == 100);
}

TEST_CASE("a T-junction: blocks 2 and 3 cells tall side by side, unmerged: warning") {
  const Mesh m = side_by_side(make_structured_quads(2, 2, 0, 0.5, 0, 1), make_structured_quads(2, 3, 0.5 + 1e-6, 1, 0, 1));
  validate_mesh(m, "t.msh");
  // the 2 edges of x = 0.5 (length 1/2) against the 3 of x = 0.5 + 1e-6 (1/3): overlaps of 1/3,
  // 1/6, 1/6, 1/3; the middle right edge lies on both left edges, a node of each side lies near the
  // interior of an edge of the other
  const auto pairs = overlapping_edges(m, boundary_free_edges(m));
  CHECK(pairs.size() == 4);
  const auto w = boundary_warnings(m);
  REQUIRE(w.size() == 1);
  CHECK(w[0].rfind("5 boundary edges lie on other boundary edges (4 pairs, at most 1.000e-06 apart", 0) == 0);
  // the same blocks exactly on x = 0.5 (what validate_mesh refuses: cells meeting without sharing
  // an edge) lie on each other too, gap 0
  const Mesh z = side_by_side(make_structured_quads(2, 2, 0, 0.5, 0, 1), make_structured_quads(2, 3, 0.5, 1, 0, 1));
  CHECK(overlapping_edges(z, boundary_free_edges(z)).size() == 4);
}

TEST_CASE("edges that only touch or meet at an angle are not on each other") {
  // two squares touching at a corner within 1e-6 (a bow tie): their edges there are
  // perpendicular or run the same way, and overlap nowhere
  const Mesh m = side_by_side(make_structured_quads(2, 2, 0, 0.5, 0, 0.5), make_structured_quads(2, 2, 0.5 + 1e-6, 1, 0.5, 1));
  CHECK(boundary_warnings(m).empty());
  // two blocks one above the other, their common outer side (y = 0 and y = 1) unmerged at x = 0.5:
  // the consecutive edges of the bottom side run the same way
  const Mesh s = side_by_side(make_structured_quads(2, 2, 0, 0.5, 0, 1), make_structured_quads(2, 2, 0.5 + 1e-6, 1, 0, 1));
  for (const EdgeOverlap& p : overlapping_edges(s, boundary_free_edges(s))) CHECK(p.gap < 2e-6);
  CHECK(overlapping_edges(s, boundary_free_edges(s)).size() == 2);
}
