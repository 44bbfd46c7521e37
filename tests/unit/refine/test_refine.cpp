// Tests of lib/refine: uniform and fixed-fraction refinement with hanging nodes (thesis §2.5).
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <set>

#include "core/error.hpp"
#include "mesh/mesh.hpp"
#include "mesh/topology.hpp"
#include "mesh/validate.hpp"
#include "refine/balance.hpp"
#include "refine/cell_edges.hpp"
#include "refine/fixed_fraction.hpp"
#include "refine/refine.hpp"
#include "refine/split.hpp"

using namespace quadapt;

namespace {

using Key = std::pair<int, int>;
Key key(int a, int b) { return a < b ? Key{a, b} : Key{b, a}; }

std::map<int, double> boundary_length_per_group(const Mesh& m) {
  std::map<int, double> len;
  for (const auto& be : m.boundary) len[be.group] += (m.nodes[be.v[1]] - m.nodes[be.v[0]]).norm();
  return len;
}

/// Independent check that a mesh is a valid conforming-or-2:1 quad mesh:
///  - every cell counter-clockwise with positive area, areas sum to `area`;
///  - every interior face conforming or one half of a coarse edge split at its midpoint into
///    exactly two faces (a 4:1 edge would leave unmatched pieces, which build_topology reports as
///    boundary faces without a group: none may exist);
///  - the foundation's validate_mesh (all quads, hanging nodes allowed) accepts it;
///  - the boundary faces are exactly the Mesh::boundary edges (same groups) and each group keeps
///    its length.
void check_mesh(const Mesh& m, double area, const std::map<int, double>& group_len) {
  ValidateOptions vo;
  vo.require = CellKind::Quads;
  CHECK_NOTHROW(validate_mesh(m, "refined", vo));
  for (int c = 0; c < m.num_cells(); ++c) {
    REQUIRE(m.cells[c].is_quad());
    REQUIRE(cell_area(m, c) > 0);
  }
  CHECK(total_area(m) == doctest::Approx(area).epsilon(1e-12));
  Topology t = build_topology(m);
  std::map<Key, int> bedges;
  for (const auto& be : m.boundary) {
    CHECK(bedges.count(key(be.v[0], be.v[1])) == 0);
    bedges[key(be.v[0], be.v[1])] = be.group;
  }
  std::map<std::pair<int, int>, std::vector<const Face*>> coarse;  // (cell, edge) -> faces
  double bface_len = 0;
  for (const Face& f : t.faces) {
    if (f.is_boundary()) {
      REQUIRE(f.group >= 0);  // an unmatched interior piece would have group -1
      bface_len += f.length;
      continue;
    }
    if (f.is_conforming()) continue;
    // side 1 is the fine side: its whole edge
    CHECK(f.s_a[1] == 1.0);
    CHECK(f.s_b[1] == 0.0);
    coarse[{f.cell[0], f.local_edge[0]}].push_back(&f);
  }
  for (auto& [ce, fs] : coarse) {
    REQUIRE(fs.size() == 2);
    double lo0 = std::min(fs[0]->s_a[0], fs[0]->s_b[0]), hi0 = std::max(fs[0]->s_a[0], fs[0]->s_b[0]);
    double lo1 = std::min(fs[1]->s_a[0], fs[1]->s_b[0]), hi1 = std::max(fs[1]->s_a[0], fs[1]->s_b[0]);
    if (lo0 > lo1) {
      std::swap(lo0, lo1);
      std::swap(hi0, hi1);
    }
    CHECK(lo0 == 0.0);
    CHECK(hi1 == 1.0);
    CHECK(hi0 == doctest::Approx(0.5).epsilon(1e-12));
    CHECK(lo1 == doctest::Approx(0.5).epsilon(1e-12));
  }
  int nb = 0;
  for (const Face& f : t.faces) nb += f.is_boundary();
  CHECK(nb == static_cast<int>(m.boundary.size()));
  auto len = boundary_length_per_group(m);
  CHECK(len.size() == group_len.size());
  for (auto& [g, l] : group_len) CHECK(len[g] == doctest::Approx(l).epsilon(1e-12));
  double total = 0;
  for (auto& [g, l] : group_len) total += l;
  CHECK(bface_len == doctest::Approx(total).epsilon(1e-12));
}

Mesh refine_by(const Mesh& m, const std::vector<double>& ind, double F, RefineStats* s = nullptr) {
  Mesh in = m;
  in.set_field(CellField{"ind", 1, ind});
  RefineOptions opt;
  opt.mode = RefineOptions::Mode::Fraction;
  opt.fraction = F;
  opt.by = "ind";
  return refine_mesh(in, opt, s);
}

}  // namespace

TEST_CASE("uniform refinement: N cells -> 4N, (n+1)^2 nodes -> (2n+1)^2, no hanging nodes") {
  for (int n : {1, 2, 5}) {
    Mesh m = make_structured_quads(n, n);
    auto glen = boundary_length_per_group(m);
    RefineOptions opt;
    RefineStats s;
    Mesh r = refine_mesh(m, opt, &s);
    CHECK(r.num_cells() == 4 * n * n);
    CHECK(r.num_nodes() == (2 * n + 1) * (2 * n + 1));
    CHECK(r.boundary.size() == 2 * m.boundary.size());
    CHECK(s.cells_before == n * n);
    CHECK(s.cells_after == 4 * n * n);
    CHECK(s.flagged == n * n);
    CHECK(s.added_by_balance == 0);
    CHECK(s.hanging_after == 0);
    check_mesh(r, 1.0, glen);
    // The result is the 2n x 2n grid: the same node set.
    Mesh g = make_structured_quads(2 * n, 2 * n);
    std::set<std::pair<double, double>> a, b;
    auto q = [](double x) { return std::round(x * 1e12) * 1e-12; };  // midpoints round differently
    for (auto& p : r.nodes) a.insert({q(p.x()), q(p.y())});
    for (auto& p : g.nodes) b.insert({q(p.x()), q(p.y())});
    CHECK(a == b);
    // Names survive.
    REQUIRE(r.groups.size() == 4);
    CHECK(r.groups[0].name == "bottom");
    CHECK(r.groups[3].name == "left");
    CHECK(r.domain_tag == m.domain_tag);
  }
}

TEST_CASE("uniform refinement of a perturbed mesh keeps area and boundary lengths") {
  Mesh m = make_perturbed_quads(4, 3, 0.3, 7);
  auto glen = boundary_length_per_group(m);
  Mesh r = refine_mesh(refine_mesh(m, {}), {});
  CHECK(r.num_cells() == 16 * 12);
  CHECK(r.num_nodes() == 17 * 13);
  check_mesh(r, 1.0, glen);
}

TEST_CASE("one flagged interior cell: 4 hanging nodes; a neighbour split reuses one") {
  Mesh m = make_structured_quads(3, 3);
  std::vector<double> ind(9, 0.0);
  ind[4] = 1.0;  // the centre cell
  RefineStats s;
  Mesh r = refine_by(m, ind, 1.0 / 9, &s);
  CHECK(s.flagged == 1);
  CHECK(s.added_by_balance == 0);
  CHECK(r.num_cells() == 12);
  CHECK(r.num_nodes() == 16 + 5);
  CHECK(s.hanging_after == 4);
  CHECK(count_hanging_nodes(r) == 4);
  check_mesh(r, 1.0, boundary_length_per_group(m));

  // Split the east neighbour (old cell 5, now at index 3 + 4 = 8... find it by centroid).
  int east = -1;
  for (int c = 0; c < r.num_cells(); ++c)
    if ((cell_centroid(r, c) - Vec2(2.5 / 3, 1.5 / 3)).norm() < 1e-12) east = c;
  REQUIRE(east >= 0);
  CellEdges ce = classify_cell_edges(r, build_topology(r));
  int coarse_edges = 0;
  for (int e = 0; e < 4; ++e) coarse_edges += ce[east][e].kind == EdgeKind::Coarse;
  CHECK(coarse_edges == 1);
  std::vector<double> ind2(r.num_cells(), 0.0);
  ind2[east] = 1.0;
  RefineStats s2;
  Mesh r2 = refine_by(r, ind2, 1.0 / r.num_cells(), &s2);
  CHECK(s2.added_by_balance == 0);
  CHECK(r2.num_nodes() == 21 + 4);  // 3 new edge nodes + centre: the hanging node is reused
  CHECK(s2.hanging_before == 4);
  CHECK(s2.hanging_after == 4 - 1 + 2);  // one stops hanging; new ones on the top and bottom cells
  check_mesh(r2, 1.0, boundary_length_per_group(m));
}

TEST_CASE("balance (thesis Fig. 2.2): a fine cell next to a coarse one forces the coarse split") {
  Mesh m = make_structured_quads(2, 1);  // cells [0,.5]x[0,1], [.5,1]x[0,1]
  Mesh r = refine_mesh(m, {}, nullptr);  // 4x2
  // Refine the cell [0.25,0.5]x[0,0.5] only -> neighbours [0.5,0.75]x[0,0.5] (same level) fine.
  std::vector<double> ind(r.num_cells(), 0.0);
  for (int c = 0; c < r.num_cells(); ++c)
    if ((cell_centroid(r, c) - Vec2(0.375, 0.25)).norm() < 1e-12) ind[c] = 1;
  Mesh r2 = refine_by(r, ind, 1.0 / r.num_cells());
  // Now flag the small cell [0.375,0.5]x[0,0.25]: it touches x = 0.5 where the neighbour
  // is one level coarser ([0.5,0.75]x[0,0.5]) -> that neighbour must be split as well.
  std::vector<double> ind2(r2.num_cells(), 0.0);
  int small = -1;
  for (int c = 0; c < r2.num_cells(); ++c)
    if ((cell_centroid(r2, c) - Vec2(0.4375, 0.125)).norm() < 1e-12) small = c;
  REQUIRE(small >= 0);
  ind2[small] = 1;
  RefineStats s;
  Mesh r3 = refine_by(r2, ind2, 1.0 / r2.num_cells(), &s);
  CHECK(s.flagged == 1);
  CHECK(s.added_by_balance == 1);
  CHECK(r3.num_cells() == r2.num_cells() + 6);
  check_mesh(r3, 1.0, boundary_length_per_group(m));

  // Chain: flagging a cell three levels below its coarsest neighbours forces a cascade.
  Mesh c0 = make_structured_quads(1, 1);
  Mesh c1 = refine_mesh(c0, {});  // 4 cells of level 1
  std::vector<double> i1(4, 0.0);
  i1[0] = 1;  // bottom-left
  Mesh c2 = refine_by(c1, i1, 0.25);
  std::vector<double> i2(c2.num_cells(), 0.0);
  for (int c = 0; c < c2.num_cells(); ++c)
    if ((cell_centroid(c2, c) - Vec2(0.375, 0.375)).norm() < 1e-12) i2[c] = 1;  // top-right child
  RefineStats s2;
  Mesh c3 = refine_by(c2, i2, 1.0 / c2.num_cells(), &s2);
  CHECK(s2.added_by_balance == 2);  // the level-1 cells to its right and above
  check_mesh(c3, 1.0, boundary_length_per_group(c0));
}

TEST_CASE("property: 2:1 balance, area and boundary on random flag patterns (many seeds)") {
  int total_balanced = 0;
  for (unsigned seed = 1; seed <= 60; ++seed) {
    std::mt19937 rng(seed);
    const int nx = 1 + static_cast<int>(rng() % 4), ny = 1 + static_cast<int>(rng() % 4);
    Mesh m = make_structured_quads(nx, ny, 0.0, 2.0, -1.0, 0.5);
    const double area = 2.0 * 1.5;
    const auto glen = boundary_length_per_group(m);
    // Level of each cell tracked independently of the geometry: through a scalar field "level"
    // copied to children (keep_scalar_fields), incremented where a parent was split.
    std::vector<int> level(m.num_cells(), 0);
    const int rounds = 4 + static_cast<int>(rng() % 3);
    for (int r = 0; r < rounds; ++r) {
      const int n = m.num_cells();
      std::uniform_real_distribution<double> u(0.0, 1.0);
      std::vector<double> ind(n);
      for (auto& x : ind) x = u(rng);
      const double F = 0.05 + 0.4 * u(rng);
      // keep the parent index to recover levels
      Mesh in = m;
      std::vector<double> id(n);
      for (int c = 0; c < n; ++c) id[c] = c;
      in.set_field(CellField{"id", 1, id});
      in.set_field(CellField{"ind", 1, ind});
      RefineOptions opt;
      opt.mode = RefineOptions::Mode::Fraction;
      opt.fraction = F;
      opt.by = "ind";
      opt.keep_scalar_fields = true;
      RefineStats s;
      Mesh out = refine_mesh(in, opt, &s);
      CHECK(s.flagged == fraction_count(F, n));
      CHECK(s.cells_after == n + 3 * s.split);
      total_balanced += s.added_by_balance;
      const CellField* pid = out.cell_field("id");
      REQUIRE(pid != nullptr);
      std::vector<int> kids(n, 0);
      for (int c = 0; c < out.num_cells(); ++c) kids[static_cast<int>((*pid)(c))]++;
      std::vector<int> newlevel(out.num_cells());
      for (int c = 0; c < out.num_cells(); ++c) {
        int p = static_cast<int>((*pid)(c));
        CHECK((kids[p] == 1 || kids[p] == 4));
        newlevel[c] = level[p] + (kids[p] == 4);
      }
      // every cell flagged by the indicator was split
      for (int c = 0; c < n; ++c)
        if (ind[c] >= 0 && kids[c] == 1) {
          int larger = 0;
          for (int d = 0; d < n; ++d) larger += ind[d] > ind[c];
          CHECK(larger >= s.flagged);
        }
      level = newlevel;
      m = out;
      m.clear_fields();
      check_mesh(m, area, glen);
      // 2:1 across every face, checked on the tracked levels and on the areas.
      Topology t = build_topology(m);
      for (const Face& f : t.faces) {
        if (f.is_boundary()) continue;
        const int l0 = level[f.cell[0]], l1 = level[f.cell[1]];
        CHECK(std::abs(l0 - l1) <= 1);
        if (!f.is_conforming()) CHECK(l1 == l0 + 1);
        const double a0 = cell_area(m, f.cell[0]), a1 = cell_area(m, f.cell[1]);
        CHECK(a0 == doctest::Approx(area / (nx * ny) / std::pow(4.0, l0)).epsilon(1e-9));
        CHECK(a1 == doctest::Approx(area / (nx * ny) / std::pow(4.0, l1)).epsilon(1e-9));
      }
    }
  }
  CHECK(total_balanced > 0);  // the property test exercised the balancing
}

TEST_CASE("an input with a hanging node that we did not make (not at index order)") {
  // Coarse cell beside two fine cells, as in the topology test.
  Mesh m;
  m.nodes = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {1, 0.5}, {1.5, 0}, {1.5, 0.5}, {1.5, 1}};
  m.cells = {Cell{{0, 1, 2, 3}, 4}, Cell{{1, 5, 6, 4}, 4}, Cell{{4, 6, 7, 2}, 4}};
  m.groups = {{1, "wall"}};
  m.boundary = {{{0, 1}, 0}, {{1, 5}, 0}, {{5, 6}, 0}, {{6, 7}, 0}, {{7, 2}, 0}, {{2, 3}, 0}, {{3, 0}, 0}};
  auto glen = boundary_length_per_group(m);
  CHECK(count_hanging_nodes(m) == 1);
  // Flag a fine cell only: the coarse neighbour must follow.
  RefineStats s;
  Mesh r = refine_by(m, {0.0, 1.0, 0.5}, 0.3, &s);
  CHECK(s.flagged == 1);
  CHECK(s.added_by_balance == 1);
  CHECK(r.num_cells() == 3 + 6);
  check_mesh(r, 1.5, glen);
  // Uniform refinement of it: still 2:1, the hanging node count doubles.
  Mesh u = refine_mesh(m, {});
  CHECK(count_hanging_nodes(u) == 2);
  check_mesh(u, 1.5, glen);
}

TEST_CASE("fixed fraction: count and choice of cells") {
  CHECK(fraction_count(0.3, 10) == 3);  // 0.3*10 = 3.0000000000000004 must not become 4
  CHECK(fraction_count(0.3, 11) == 4);
  CHECK(fraction_count(1.0, 7) == 7);
  CHECK(fraction_count(1e-6, 7) == 1);
  auto f = flag_largest_fraction({0.1, 5.0, 2.0, 2.0, -1.0}, 0.5);  // 3 of 5; tie -> lower index
  CHECK(f == std::vector<char>{0, 1, 1, 1, 0});
  auto g = flag_largest_fraction({1.0, 1.0, 1.0, 1.0}, 0.5);
  CHECK(g == std::vector<char>{1, 1, 0, 0});
  // F = 1 is uniform refinement.
  Mesh m = make_structured_quads(3, 2);
  Mesh a = refine_by(m, std::vector<double>(6, 1.0), 1.0);
  Mesh b = refine_mesh(m, {});
  CHECK(a.num_cells() == b.num_cells());
  CHECK(a.num_nodes() == b.num_nodes());
}

TEST_CASE("bad input: fraction, missing / wrong fields, triangles") {
  Mesh m = make_structured_quads(2, 2);
  m.set_field(CellField{"B", 1, {1, 2, 3, 4}});
  m.cell_fields.push_back(CellField{"Vinv", 9, std::vector<double>(36, 1.0)});
  m.cell_fields.push_back(CellField{"short", 1, {1, 2, 3}});
  m.cell_fields.push_back(CellField{"nan", 1, {1, std::numeric_limits<double>::quiet_NaN(), 3, 4}});
  m.cell_node_fields.push_back(CellNodeField{"u", 1, 4, 1, std::vector<double>(16, 0.0)});
  RefineOptions opt;
  opt.mode = RefineOptions::Mode::Fraction;
  opt.by = "B";
  for (double F : {0.0, -0.1, 1.5, std::numeric_limits<double>::quiet_NaN()}) {
    opt.fraction = F;
    CHECK_THROWS_AS(refine_mesh(m, opt, nullptr, "in.msh"), InputError);
  }
  opt.fraction = 0.3;
  auto message = [&](const std::string& by) {
    RefineOptions o = opt;
    o.by = by;
    try {
      refine_mesh(m, o, nullptr, "in.msh");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK(message("A1").find("in.msh: no cell field 'A1'") == 0);
  CHECK(message("A1").find("B, Vinv") != std::string::npos);
  CHECK(message("u").find("per-node field") != std::string::npos);
  CHECK(message("Vinv").find("9 components") != std::string::npos);
  CHECK(message("short").find("3 values for 4 cells") != std::string::npos);
  CHECK(message("nan").find("is nan in cell 2 (centroid (0.75, 0.25))") != std::string::npos);  // numbered from 1
  CHECK(message("B") == "no error");

  Mesh t;
  t.nodes = {{0, 0}, {1, 0}, {0, 1}};
  t.cells = {Cell{{0, 1, 2, -1}, 3}};
  CHECK_THROWS_AS(refine_mesh(t, {}, nullptr, "tri.msh"), InputError);
}

TEST_CASE("fields: dropped by default, scalar cell fields copied to children on request") {
  Mesh m = make_structured_quads(2, 1);
  m.set_field(CellField{"B", 1, {3.0, 7.0}});
  m.set_field(CellField{"Vinv", 9, std::vector<double>(18, 1.0)});
  m.set_field(CellNodeField{"u", 1, 4, 1, std::vector<double>(8, 0.0)});
  Mesh r = refine_mesh(m, {});
  CHECK(r.cell_fields.empty());
  CHECK(r.cell_node_fields.empty());
  RefineOptions keep;
  keep.keep_scalar_fields = true;
  Mesh k = refine_mesh(m, keep);
  REQUIRE(k.cell_fields.size() == 1);
  CHECK(k.cell_node_fields.empty());
  const CellField& b = k.cell_fields[0];
  CHECK(b.name == "B");
  REQUIRE(b.values.size() == 8);
  for (int c = 0; c < 8; ++c) CHECK(b(c) == (cell_centroid(k, c).x() < 0.5 ? 3.0 : 7.0));
}

TEST_CASE("split_cells refuses unbalanced flags") {
  Mesh m = make_structured_quads(2, 1);
  std::vector<double> ind{1.0, 0.0};
  Mesh r = refine_by(m, ind, 0.5);
  CellEdges ce = classify_cell_edges(r, build_topology(r));
  std::vector<char> flags(r.num_cells(), 0);
  for (int c = 0; c < r.num_cells(); ++c)
    if ((cell_centroid(r, c) - Vec2(0.375, 0.25)).norm() < 1e-12) flags[c] = 1;
  CHECK_FALSE(flags_balanced(ce, flags));
  CHECK_THROWS_AS(split_cells(r, ce, flags), Error);
  CHECK(balance_flags(ce, flags) == 1);
  CHECK(flags_balanced(ce, flags));
  CHECK_NOTHROW(split_cells(r, ce, flags));
}

TEST_CASE("a 4:1 interface (four faces along one coarse edge) is refused, not taken for a boundary") {
  // Coarse cell [0,1]^2 beside four cells of height 1/4 on [1,1.25] x [0,1].
  Mesh m;
  m.nodes = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int j = 1; j <= 3; ++j) m.nodes.push_back({1, j / 4.0});      // 4, 5, 6
  for (int j = 0; j <= 4; ++j) m.nodes.push_back({1.25, j / 4.0});   // 7 .. 11
  const int right[5] = {1, 4, 5, 6, 2};
  m.cells.push_back(Cell{{0, 1, 2, 3}, 4});
  for (int j = 0; j < 4; ++j) m.cells.push_back(Cell{{right[j], 7 + j, 8 + j, right[j + 1]}, 4});
  CHECK_THROWS_WITH_AS(refine_mesh(m, {}, nullptr, "x.msh"), doctest::Contains("x.msh: "), InputError);
  // cells and their edges numbered from 1, as in every message (docs/exit-codes.md)
  CHECK_THROWS_WITH_AS(refine_mesh(m, {}), doctest::Contains("edge 2 of cell 1 (centroid (0.5, 0.5))"), InputError);
  // The same fine cells against two coarse halves (2:1) are fine.
  Mesh ok = m;
  ok.cells[0] = Cell{{0, 1, 5, 3}, 4};
  ok.nodes[3] = {0, 0.5};
  ok.cells.push_back(Cell{{3, 5, 2, 12}, 4});
  ok.nodes.push_back({0, 1});
  CHECK_NOTHROW(refine_mesh(ok, {}));
}
