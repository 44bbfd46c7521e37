// canonical_order (lib/mesh/canonical.hpp): a renumbered mesh — nodes and cells in another
// order, cell vertex lists starting at other corners, boundary edges shuffled — has the same
// canonical form, and fields and curved control points move with their cells.
#include <doctest/doctest.h>

#include <algorithm>
#include <numeric>
#include <random>

#include "curved_disk.hpp"
#include "mesh/canonical.hpp"
#include "mesh/mesh.hpp"

using namespace quadapt;

namespace {

/// m with nodes and cells permuted at random, every cell's vertex list rotated by a random
/// amount (when `rotate`), and the boundary edges shuffled.
Mesh renumbered(const Mesh& m, unsigned seed, bool rotate) {
  std::mt19937 rng(seed);
  std::vector<int> new_node(static_cast<size_t>(m.num_nodes()));
  std::iota(new_node.begin(), new_node.end(), 0);
  std::shuffle(new_node.begin(), new_node.end(), rng);
  std::vector<int> old_cell(static_cast<size_t>(m.num_cells()));
  std::iota(old_cell.begin(), old_cell.end(), 0);
  std::shuffle(old_cell.begin(), old_cell.end(), rng);
  Mesh out = m;
  for (int i = 0; i < m.num_nodes(); ++i) out.nodes[new_node[i]] = m.nodes[i];
  for (int c = 0; c < m.num_cells(); ++c) {
    Cell cell = m.cells[old_cell[c]];
    for (int k = 0; k < cell.nv; ++k) cell.v[k] = new_node[cell.v[k]];
    if (rotate) std::rotate(cell.v.begin(), cell.v.begin() + rng() % cell.nv, cell.v.begin() + cell.nv);
    out.cells[c] = cell;
  }
  if (m.is_curved()) {
    const size_t per = static_cast<size_t>(m.curved.per_cell());
    for (int c = 0; c < m.num_cells(); ++c)
      std::copy_n(m.curved.points.begin() + old_cell[c] * per, per, out.curved.points.begin() + c * per);
  }
  for (CellField& f : out.cell_fields) {
    const CellField* src = m.cell_field(f.name);
    for (int c = 0; c < m.num_cells(); ++c)
      for (int k = 0; k < f.ncomp; ++k) f(c, k) = (*src)(old_cell[c], k);
  }
  for (BoundaryEdge& e : out.boundary) e.v = {new_node[e.v[0]], new_node[e.v[1]]};
  std::shuffle(out.boundary.begin(), out.boundary.end(), rng);
  return out;
}

void check_same(const Mesh& a, const Mesh& b) {
  REQUIRE(a.num_nodes() == b.num_nodes());
  REQUIRE(a.num_cells() == b.num_cells());
  for (int i = 0; i < a.num_nodes(); ++i) CHECK(a.nodes[i] == b.nodes[i]);
  for (int c = 0; c < a.num_cells(); ++c) CHECK(a.cells[c].v == b.cells[c].v);
  REQUIRE(a.boundary.size() == b.boundary.size());
  for (size_t e = 0; e < a.boundary.size(); ++e) {
    CHECK(a.boundary[e].v == b.boundary[e].v);
    CHECK(a.boundary[e].group == b.boundary[e].group);
  }
  REQUIRE(a.cell_fields.size() == b.cell_fields.size());
  for (size_t f = 0; f < a.cell_fields.size(); ++f) CHECK(a.cell_fields[f].values == b.cell_fields[f].values);
  CHECK(a.curved.points == b.curved.points);
}

}  // namespace

TEST_CASE("canonical order: any renumbering of a mesh gives the same canonical mesh") {
  Mesh m = make_perturbed_quads(7, 5, 0.3, 11);
  CellField f;
  f.name = "Vinv";
  f.ncomp = 2;
  for (int c = 0; c < m.num_cells(); ++c) {
    const Vec2 x = cell_centroid(m, c);
    f.values.push_back(x.x());
    f.values.push_back(x.y());
  }
  m.set_field(f);
  Renumbering r;
  const Mesh ref = canonical_order(m, &r);
  // the fields moved with their cells: each cell's field is still its own centroid
  for (int c = 0; c < ref.num_cells(); ++c) {
    CHECK(ref.cell_fields[0](c, 0) == cell_centroid(m, r.old_cell[c]).x());
    CHECK(cell_area(ref, c) == doctest::Approx(cell_area(m, r.old_cell[c])).epsilon(1e-14));
    CHECK(cell_area(ref, c) > 0);  // counter-clockwise kept
    const auto mn = std::min_element(ref.cells[c].v.begin(), ref.cells[c].v.end());
    CHECK(mn == ref.cells[c].v.begin());  // starts at its smallest node
  }
  for (int i = 0; i < m.num_nodes(); ++i) CHECK(ref.nodes[r.new_node[i]] == m.nodes[i]);
  // nodes sorted by (x, y)
  for (int i = 1; i < ref.num_nodes(); ++i)
    CHECK((ref.nodes[i - 1].x() < ref.nodes[i].x() ||
           (ref.nodes[i - 1].x() == ref.nodes[i].x() && ref.nodes[i - 1].y() < ref.nodes[i].y())));
  check_same(canonical_order(ref), ref);  // idempotent
  for (unsigned seed : {1u, 2u, 3u}) {
    CAPTURE(seed);
    check_same(canonical_order(renumbered(m, seed, true)), ref);
  }
}

TEST_CASE("canonical order: curved cells keep their first vertex and carry their control points") {
  const Mesh m = curvedtest::curved_disk(3, 3);
  REQUIRE(m.is_curved());
  Renumbering r;
  const Mesh ref = canonical_order(m, &r);
  for (int c = 0; c < ref.num_cells(); ++c) {
    CHECK(cell_area(ref, c) == doctest::Approx(cell_area(m, r.old_cell[c])).epsilon(1e-13));
    CHECK(ref.cells[c].v[0] == r.new_node[m.cells[r.old_cell[c]].v[0]]);
  }
  for (unsigned seed : {4u, 5u}) check_same(canonical_order(renumbered(m, seed, false)), ref);
}
