#include "refine/split.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <string>
#include <utility>

#include "core/error.hpp"
#include "mesh/label.hpp"
#include "refine/balance.hpp"

namespace quadapt {

Mesh split_cells(const Mesh& m, const CellEdges& edges, const std::vector<char>& flags,
                 bool keep_scalar_fields) {
  if (flags.size() != m.cells.size() || edges.size() != m.cells.size())
    throw Error("split_cells: flags/edges do not match the mesh's " + std::to_string(m.num_cells()) +
                " cells");
  if (!flags_balanced(edges, flags))
    throw Error("split_cells: the flags are not 2:1 balanced (call balance_flags first)");

  Mesh out;
  out.nodes = m.nodes;
  out.groups = m.groups;
  out.domain_name = m.domain_name;
  out.domain_tag = m.domain_tag;

  using EdgeKey = std::pair<int, int>;
  auto key = [](int a, int b) { return a < b ? EdgeKey{a, b} : EdgeKey{b, a}; };
  std::map<EdgeKey, int> midpoint;  // new edge nodes (never hanging-node reuses)
  auto edge_node = [&](int a, int b) {
    auto [it, inserted] = midpoint.try_emplace(key(a, b), out.num_nodes());
    if (inserted) out.nodes.push_back(0.5 * (m.nodes[a] + m.nodes[b]));
    return it->second;
  };

  std::vector<int> parent;  // parent of each output cell
  out.cells.reserve(m.cells.size() + 3 * static_cast<size_t>(std::count(flags.begin(), flags.end(), 1)));
  for (int c = 0; c < m.num_cells(); ++c) {
    const Cell& cell = m.cells[c];
    if (!flags[c]) {
      out.cells.push_back(cell);
      parent.push_back(c);
      continue;
    }
    if (!cell.is_quad())
      throw InputError("mesh", cell_label(m, c) + " is a triangle; refine splits quads only");
    int mid[4];
    for (int e = 0; e < 4; ++e) {
      const CellEdge& ce = edges[c][e];
      mid[e] = ce.kind == EdgeKind::Coarse ? ce.hanging_node : edge_node(cell.v[e], cell.v[(e + 1) % 4]);
    }
    const int centre = out.num_nodes();
    out.nodes.push_back(map_to_physical(m, c, 0.0, 0.0));
    const auto& v = cell.v;
    const std::array<std::array<int, 4>, 4> kids{{{v[0], mid[0], centre, mid[3]},
                                                  {mid[0], v[1], mid[1], centre},
                                                  {centre, mid[1], v[2], mid[2]},
                                                  {mid[3], centre, mid[2], v[3]}}};
    for (const auto& k : kids) {
      Cell child;
      child.nv = 4;
      child.v = k;
      out.cells.push_back(child);
      parent.push_back(c);
    }
  }

  for (const BoundaryEdge& be : m.boundary) {
    auto it = midpoint.find(key(be.v[0], be.v[1]));
    if (it == midpoint.end()) {
      out.boundary.push_back(be);
      continue;
    }
    out.boundary.push_back({{be.v[0], it->second}, be.group});
    out.boundary.push_back({{it->second, be.v[1]}, be.group});
  }

  if (keep_scalar_fields) {
    for (const CellField& f : m.cell_fields) {
      if (f.ncomp != 1 || f.num_cells() != m.num_cells()) continue;
      CellField g;
      g.name = f.name;
      g.ncomp = 1;
      g.values.resize(parent.size());
      for (size_t i = 0; i < parent.size(); ++i) g.values[i] = f(parent[i]);
      out.cell_fields.push_back(std::move(g));
    }
  }
  return out;
}

}  // namespace quadapt
