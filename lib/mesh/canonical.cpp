#include "mesh/canonical.hpp"

#include <algorithm>
#include <climits>
#include <numeric>
#include <tuple>

namespace quadapt {

Mesh canonical_order(const Mesh& m, Renumbering* r) {
  const int nn = m.num_nodes(), nc = m.num_cells();
  // nodes by (x, y)
  std::vector<int> old_node(static_cast<size_t>(nn));
  std::iota(old_node.begin(), old_node.end(), 0);
  std::stable_sort(old_node.begin(), old_node.end(), [&](int a, int b) {
    const Vec2 &p = m.nodes[a], &q = m.nodes[b];
    return p.x() < q.x() || (p.x() == q.x() && p.y() < q.y());
  });
  std::vector<int> new_node(static_cast<size_t>(nn));
  for (int i = 0; i < nn; ++i) new_node[old_node[i]] = i;

  // cells by their sorted new node indices
  const bool rotate = !m.is_curved() && m.cell_node_fields.empty();
  std::vector<Cell> renamed(m.cells);
  std::vector<std::array<int, 4>> key(static_cast<size_t>(nc));
  for (int c = 0; c < nc; ++c) {
    Cell& cell = renamed[c];
    for (int k = 0; k < cell.nv; ++k) cell.v[k] = new_node[cell.v[k]];
    if (rotate) {
      const int first = static_cast<int>(std::min_element(cell.v.begin(), cell.v.begin() + cell.nv) - cell.v.begin());
      std::rotate(cell.v.begin(), cell.v.begin() + first, cell.v.begin() + cell.nv);
    }
    key[c] = {INT_MAX, INT_MAX, INT_MAX, INT_MAX};
    std::copy(cell.v.begin(), cell.v.begin() + cell.nv, key[c].begin());
    std::sort(key[c].begin(), key[c].begin() + cell.nv);
  }
  std::vector<int> old_cell(static_cast<size_t>(nc));
  std::iota(old_cell.begin(), old_cell.end(), 0);
  std::stable_sort(old_cell.begin(), old_cell.end(), [&](int a, int b) { return key[a] < key[b]; });

  Mesh out;
  out.groups = m.groups;
  out.domain_name = m.domain_name;
  out.domain_tag = m.domain_tag;
  out.frame_convention = m.frame_convention;
  out.solved_case = m.solved_case;
  out.nodes.resize(static_cast<size_t>(nn));
  for (int i = 0; i < nn; ++i) out.nodes[i] = m.nodes[old_node[i]];
  out.cells.resize(static_cast<size_t>(nc));
  for (int c = 0; c < nc; ++c) out.cells[c] = renamed[old_cell[c]];

  out.curved.order = m.curved.order;
  if (m.is_curved()) {
    const size_t per = static_cast<size_t>(m.curved.per_cell());
    out.curved.points.resize(m.curved.points.size());
    for (int c = 0; c < nc; ++c)
      std::copy_n(m.curved.points.begin() + old_cell[c] * per, per, out.curved.points.begin() + c * per);
  }
  for (const CellField& f : m.cell_fields) {
    CellField g = f;
    const size_t w = static_cast<size_t>(f.ncomp);
    for (int c = 0; c < nc; ++c) std::copy_n(f.values.begin() + old_cell[c] * w, w, g.values.begin() + c * w);
    out.cell_fields.push_back(std::move(g));
  }
  for (const CellNodeField& f : m.cell_node_fields) {
    CellNodeField g = f;
    const size_t w = static_cast<size_t>(f.per_cell) * f.ncomp;
    for (int c = 0; c < nc; ++c) std::copy_n(f.cell(old_cell[c]), w, g.cell(c));
    out.cell_node_fields.push_back(std::move(g));
  }

  out.boundary = m.boundary;
  for (BoundaryEdge& e : out.boundary) e.v = {new_node[e.v[0]], new_node[e.v[1]]};
  std::stable_sort(out.boundary.begin(), out.boundary.end(), [](const BoundaryEdge& a, const BoundaryEdge& b) {
    const auto ka = std::make_tuple(a.group, std::min(a.v[0], a.v[1]), std::max(a.v[0], a.v[1]));
    const auto kb = std::make_tuple(b.group, std::min(b.v[0], b.v[1]), std::max(b.v[0], b.v[1]));
    return ka < kb;
  });
  if (r) {
    r->new_node = std::move(new_node);
    r->old_cell = std::move(old_cell);
  }
  return out;
}

}  // namespace quadapt
