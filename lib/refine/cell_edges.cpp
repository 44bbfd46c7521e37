#include "refine/cell_edges.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <unordered_map>

#include "core/error.hpp"
#include "mesh/label.hpp"

namespace quadapt {

namespace {
struct Piece {
  double lo, hi;
  int face, side;
};
bool whole(double a, double b) { return std::min(a, b) == 0.0 && std::max(a, b) == 1.0; }

// build_topology reports the pieces of a non-conformity other than 2:1 (e.g. four fine faces
// along one coarse edge) as boundary faces. On a real boundary two free edges leaving the same
// node never overlap; at such an interface the fine edges lie inside the coarse one. Refuse them.
void check_free_edges(const Mesh& m, const CellEdges& edges) {
  struct Free {
    int cell, edge, to;
  };
  std::unordered_multimap<int, Free> at;
  for (int c = 0; c < m.num_cells(); ++c)
    for (int e = 0; e < m.cells[c].nv; ++e)
      if (edges[c][e].kind == EdgeKind::Boundary) {
        const int a = m.cells[c].v[e], b = m.cells[c].v[(e + 1) % m.cells[c].nv];
        at.emplace(a, Free{c, e, b});
        at.emplace(b, Free{c, e, a});
      }
  for (const auto& [a, f] : at) {
    const Vec2 &pa = m.nodes[a], d = m.nodes[f.to] - pa;
    const double len2 = d.squaredNorm();
    auto range = at.equal_range(a);
    for (auto it = range.first; it != range.second; ++it) {
      const Free& g = it->second;
      if (g.cell == f.cell && g.edge == f.edge) continue;
      const Vec2 q = m.nodes[g.to] - pa;
      const double s = q.dot(d) / len2;
      const double off = std::abs(d.x() * q.y() - d.y() * q.x()) / std::sqrt(len2);
      if (g.to != f.to && s > 0 && s < 1 && off <= 1e-9 * std::sqrt(len2))
        throw InputError("mesh", "edge " + number_text(f.edge) + " of " + cell_label(m, f.cell) +
                                     " is matched neither by one neighbour edge nor by two halves (cell " +
                                     number_text(g.cell) + " lies along part of it): only conforming "
                                     "and 2:1 non-conforming meshes are supported");
    }
  }
}
}  // namespace

CellEdges classify_cell_edges(const Mesh& m, const Topology& t) {
  CellEdges out(m.cells.size());
  std::vector<Piece> pieces[4];
  for (int c = 0; c < m.num_cells(); ++c) {
    const Cell& cell = m.cells[c];
    for (auto& p : pieces) p.clear();
    for (int fi : t.cell_faces[c]) {
      const Face& f = t.faces[fi];
      const int k = f.cell[0] == c ? 0 : 1;
      const int e = f.local_edge[k];
      pieces[e].push_back({std::min(f.s_a[k], f.s_b[k]), std::max(f.s_a[k], f.s_b[k]), fi, k});
    }
    for (int e = 0; e < cell.nv; ++e) {
      auto& ps = pieces[e];
      CellEdge& ce = out[c][e];
      const std::string where = cell_label(m, c) + " edge " + number_text(e);
      if (ps.size() > 2)
        throw InputError("mesh", where + " is covered by " + std::to_string(ps.size()) +
                                     " faces (only conforming and 2:1 edges are supported)");
      if (ps.empty()) continue;  // cannot happen for a topology of m; treated as boundary
      if (ps.size() == 1) {
        const Face& f = t.faces[ps[0].face];
        if (f.is_boundary()) {
          ce.kind = EdgeKind::Boundary;
          continue;
        }
        const int k = ps[0].side;
        if (!whole(ps[0].lo, ps[0].hi))
          throw InputError("mesh", where + " is only partly covered by a face");
        ce.neighbour[0] = f.cell[1 - k];
        ce.kind = whole(f.s_a[1 - k], f.s_b[1 - k]) ? EdgeKind::Conforming : EdgeKind::Fine;
        continue;
      }
      std::sort(ps.begin(), ps.end(), [](const Piece& a, const Piece& b) { return a.lo < b.lo; });
      ce.kind = EdgeKind::Coarse;
      for (int i = 0; i < 2; ++i) {
        const Face& f = t.faces[ps[i].face];
        ce.neighbour[i] = f.cell[1 - ps[i].side];
        if (ce.neighbour[i] < 0)
          throw InputError("mesh", where + " is split between a neighbour and the boundary");
      }
      // The hanging node: the end of the first fine edge that is not a vertex of this edge.
      const Face& f0 = t.faces[ps[0].face];
      const int k0 = 1 - ps[0].side;
      const Cell& fine = m.cells[f0.cell[k0]];
      const int fe = f0.local_edge[k0];
      const int a = cell.v[e], b = cell.v[(e + 1) % cell.nv];
      for (int n : {fine.v[fe], fine.v[(fe + 1) % fine.nv]})
        if (n != a && n != b) ce.hanging_node = n;
      if (ce.hanging_node < 0) throw InputError("mesh", where + ": cannot find its hanging node");
    }
  }
  check_free_edges(m, out);
  return out;
}

int count_hanging_nodes(const Mesh& m, const Topology& t) {
  CellEdges ce = classify_cell_edges(m, t);
  int n = 0;
  for (int c = 0; c < m.num_cells(); ++c)
    for (int e = 0; e < m.cells[c].nv; ++e) n += ce[c][e].kind == EdgeKind::Coarse;
  return n;
}

int count_hanging_nodes(const Mesh& m) { return count_hanging_nodes(m, build_topology(m)); }

}  // namespace quadapt
