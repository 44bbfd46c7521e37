#include "quad/subdivide.hpp"

#include <cstdint>
#include <unordered_map>

#include "core/error.hpp"
#include "mesh/label.hpp"

namespace quadapt {

namespace {
std::uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}
}  // namespace

Mesh split_to_all_quads(const Mesh& m) {
  Mesh out;
  out.groups = m.groups;
  out.domain_name = m.domain_name;
  out.domain_tag = m.domain_tag;
  out.nodes = m.nodes;
  out.nodes.reserve(m.nodes.size() + 3 * m.cells.size());
  std::unordered_map<std::uint64_t, int> mid;
  mid.reserve(2 * m.cells.size() + m.boundary.size());
  auto midpoint = [&](int a, int b) {
    auto [it, inserted] = mid.emplace(edge_key(a, b), static_cast<int>(out.nodes.size()));
    if (inserted) out.nodes.push_back(0.5 * (m.nodes[a] + m.nodes[b]));
    return it->second;
  };
  // Midpoints first, cell by cell, so numbering is deterministic.
  std::vector<std::array<int, 4>> mids(m.cells.size());
  for (size_t c = 0; c < m.cells.size(); ++c) {
    const Cell& cell = m.cells[c];
    if (cell.nv != 3 && cell.nv != 4) throw InputError("mesh: cell " + number_text(c) + " is neither a triangle nor a quad");
    for (int i = 0; i < cell.nv; ++i) mids[c][i] = midpoint(cell.v[i], cell.v[(i + 1) % cell.nv]);
  }
  out.cells.reserve(4 * m.cells.size());
  for (size_t c = 0; c < m.cells.size(); ++c) {
    const Cell& cell = m.cells[c];
    const int n = cell.nv;
    Vec2 centre = Vec2::Zero();
    for (int i = 0; i < n; ++i) centre += m.nodes[cell.v[i]];
    centre /= n;
    int ic = static_cast<int>(out.nodes.size());
    out.nodes.push_back(centre);
    for (int i = 0; i < n; ++i) {
      Cell q;
      q.nv = 4;
      q.v = {cell.v[i], mids[c][i], ic, mids[c][(i + n - 1) % n]};
      out.cells.push_back(q);
    }
  }
  out.boundary.reserve(2 * m.boundary.size());
  for (const auto& e : m.boundary) {
    auto it = mid.find(edge_key(e.v[0], e.v[1]));
    if (it == mid.end())
      throw InputError("mesh: the boundary edge between nodes " + number_text(e.v[0]) + " " + point_text(m.nodes[e.v[0]]) +
                       " and " + number_text(e.v[1]) + " " + point_text(m.nodes[e.v[1]]) + " is not an edge of any cell");
    out.boundary.push_back({{e.v[0], it->second}, e.group});
    out.boundary.push_back({{it->second, e.v[1]}, e.group});
  }
  return out;
}

}  // namespace quadapt
