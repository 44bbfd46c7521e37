// Boundary from the free edges: chaining, corner splitting, naming.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <map>

#include "mesh/boundary.hpp"

using namespace quadapt;

namespace {
/// Structured n x n grid of [0,1]^2 without the cells for which drop(i, j) holds, no boundary.
template <class F>
Mesh grid_without(int n, F drop) {
  Mesh full = make_structured_quads(n, n);
  Mesh m;
  m.nodes = full.nodes;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      if (!drop(i, j)) m.cells.push_back(full.cells[j * n + i]);
  return m;
}
std::map<std::string, int> edge_counts(const Mesh& m) {
  std::map<std::string, int> out;
  for (const auto& e : m.boundary) ++out[m.groups[e.group].name];
  return out;
}
}  // namespace

TEST_CASE("unit square: the four sides, named, like the builder's") {
  Mesh ref = make_structured_quads(5, 5);
  Mesh m = ref;
  m.boundary.clear();
  m.groups.clear();
  CHECK(complete_boundary(m) == 20);
  REQUIRE(m.groups.size() == 4);
  const char* names[] = {"bottom", "right", "top", "left"};
  for (int g = 0; g < 4; ++g) {
    CHECK(m.groups[g].name == names[g]);
    CHECK(m.groups[g].tag == g + 1);
  }
  REQUIRE(m.boundary.size() == ref.boundary.size());
  for (size_t e = 0; e < ref.boundary.size(); ++e) {  // same edges, same order, same orientation
    CHECK(m.boundary[e].v == ref.boundary[e].v);
    CHECK(m.boundary[e].group == ref.boundary[e].group);
  }
  CHECK(complete_boundary(m) == 0);  // already complete
}

TEST_CASE("L-shape: six straight curves boundary_1..6 from the lowest corner") {
  Mesh m = grid_without(4, [](int i, int j) { return i >= 2 && j >= 2; });
  CHECK(!is_unit_square(m));
  CHECK(complete_boundary(m) == 16);
  std::map<std::string, int> want = {{"boundary_1", 4}, {"boundary_2", 2}, {"boundary_3", 2},
                                     {"boundary_4", 2}, {"boundary_5", 2}, {"boundary_6", 4}};
  CHECK(edge_counts(m) == want);
  // boundary_1 is the bottom side y = 0, boundary_3 the re-entrant side y = 0.5
  for (const auto& e : m.boundary) {
    if (m.groups[e.group].name == "boundary_1") CHECK(m.nodes[e.v[0]].y() == 0.0);
    if (m.groups[e.group].name == "boundary_3") CHECK(m.nodes[e.v[0]].y() == 0.5);
  }
}

TEST_CASE("square with a square hole: outer loop first, hole split at its corners") {
  Mesh m = grid_without(4, [](int i, int j) { return i >= 1 && i <= 2 && j >= 1 && j <= 2; });
  CHECK(complete_boundary(m) == 16 + 8);
  REQUIRE(m.groups.size() == 8);
  for (int g = 0; g < 8; ++g) CHECK(m.groups[g].name == "boundary_" + std::to_string(g + 1));
  // the hole runs clockwise (domain on the left): its first curve starts at (0.25, 0.25)
  int first_hole_edge = -1;
  for (size_t e = 0; e < m.boundary.size(); ++e)
    if (m.boundary[e].group == 4) { first_hole_edge = static_cast<int>(e); break; }
  REQUIRE(first_hole_edge >= 0);
  CHECK(m.nodes[m.boundary[first_hole_edge].v[0]] == Vec2(0.25, 0.25));
}

TEST_CASE("smooth closed curves are not split; a kink between straight runs is") {
  // Annulus of 48 x 1 quads: both loops turn 7.5 degrees at every node, no straight runs.
  Mesh ring;
  const int n = 48;
  for (int k = 0; k < n; ++k)
    for (double r : {1.0, 2.0}) ring.nodes.emplace_back(r * std::cos(2 * M_PI * k / n), r * std::sin(2 * M_PI * k / n));
  for (int k = 0; k < n; ++k) {
    int a = 2 * k, b = 2 * ((k + 1) % n);
    ring.cells.push_back(Cell{{a, a + 1, b + 1, b}, 4});
  }
  for (const Cell& c : ring.cells) REQUIRE(cell_area(ring, c.v[0] / 2) > 0);
  CHECK(complete_boundary(ring) == 2 * n);
  CHECK(ring.groups.size() == 2);

  // A top side that bends by 5.7 degrees at x = 0.5 between two straight runs: split there.
  Mesh k = make_structured_quads(4, 2);
  k.boundary.clear();
  k.groups.clear();
  for (auto& p : k.nodes)
    if (p.y() == 1.0 && p.x() > 0.5) p.y() += 0.1 * (p.x() - 0.5);
  CHECK(complete_boundary(k) == 12);
  CHECK(k.groups.size() == 5);
}

TEST_CASE("hanging nodes: the split coarse edge is interior") {
  Mesh m;
  m.nodes = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {1, 0.5}, {1.5, 0}, {1.5, 0.5}, {1.5, 1}};
  m.cells = {Cell{{0, 1, 2, 3}, 4}, Cell{{1, 5, 6, 4}, 4}, Cell{{4, 6, 7, 2}, 4}};
  std::vector<EdgeNodes> fe = boundary_free_edges(m);
  CHECK(fe.size() == 7);  // 3 sides of the coarse cell + bottom, 2 x right, top of the fine ones
  for (const EdgeNodes& e : fe) {
    CHECK(!(e[0] == 1 && e[1] == 2));
    CHECK(!(e[0] == 4 || e[1] == 4));  // the hanging node is on no free edge
  }
  CHECK(complete_boundary(m) == 7);
  CHECK(m.groups.size() == 4);  // a rectangle [0,1.5]x[0,1]: four straight sides
}

/// The 3 x 3 unit square without its "left" group (group 3) and edges.
static Mesh square_without_left() {
  Mesh m = make_structured_quads(3, 3);
  std::vector<BoundaryEdge> keep;
  for (const auto& e : m.boundary)
    if (e.group != 3) keep.push_back(e);
  m.boundary = keep;
  m.groups.pop_back();
  return m;
}

TEST_CASE("partial boundary: only the missing side is added") {
  Mesh m = square_without_left();
  CHECK(complete_boundary(m) == 3);
  REQUIRE(m.groups.size() == 4);
  CHECK(m.groups[3].name == "left");
  CHECK(m.groups[3].tag == 4);
}

TEST_CASE("partial boundary with a group tagged INT_MAX: the added group takes the smallest free tag") {
  // A file may give a physical tag of 2147483647; "largest + 1" overflowed (found by fuzzing).
  Mesh m = square_without_left();
  m.groups[1].tag = std::numeric_limits<int>::max();  // tags now 1, INT_MAX, 3
  CHECK(complete_boundary(m) == 3);
  REQUIRE(m.groups.size() == 4);
  CHECK(m.groups[3].name == "left");
  CHECK(m.groups[3].tag == 2);
  m.domain_tag = std::numeric_limits<int>::max();
  const int g = m.group_index("inlet");
  CHECK(m.groups[g].tag == 4);
}
