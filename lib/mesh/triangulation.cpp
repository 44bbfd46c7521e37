#include "mesh/triangulation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <sstream>
#include <unordered_map>

#include "core/error.hpp"
#include "core/format.hpp"
#include "mesh/label.hpp"
#include "mesh/boundary.hpp"

namespace quadapt {


std::string TriangulationCheck::summary() const {
  std::ostringstream os;
  os << triangles << " triangles, " << non_positive << " with area <= 0 (min area " << min_area
     << "), area " << area << ", " << boundary_edges << " boundary edges, "
     << boundary_edges_missing << " not on exactly one triangle, " << free_edges_unlisted
     << " free triangle edges not on the boundary";
  return os.str();
}

TriangulationCheck check_triangulation(const Mesh& m) {
  TriangulationCheck c;
  std::map<std::pair<int, int>, int> count;
  c.min_area = 1e300;
  for (int k = 0; k < m.num_cells(); ++k) {
    const Cell& cl = m.cells[k];
    if (cl.nv != 3) continue;
    ++c.triangles;
    double a = cell_area(m, k);
    c.area += a;
    c.min_area = std::min(c.min_area, a);
    if (!(a > 0)) ++c.non_positive;
    for (int e = 0; e < 3; ++e) {
      int u = cl.v[e], v = cl.v[(e + 1) % 3];
      ++count[{std::min(u, v), std::max(u, v)}];
    }
  }
  if (!c.triangles) c.min_area = 0;
  std::map<std::pair<int, int>, int> bset;
  for (const auto& b : m.boundary) {
    ++c.boundary_edges;
    std::pair<int, int> key{std::min(b.v[0], b.v[1]), std::max(b.v[0], b.v[1])};
    ++bset[key];
    auto it = count.find(key);
    if (it == count.end() || it->second != 1) ++c.boundary_edges_missing;
  }
  for (const auto& [e, n] : count)
    if (n == 1 && !bset.count(e)) ++c.free_edges_unlisted;
  return c;
}

void require_triangulation(const Mesh& m, const std::string& path) {
  if (m.cells.empty()) throw InputError(path, "the mesh has no cells");
  if (m.num_quads() > 0)
    throw InputError(path, "not a triangulation: " + std::to_string(m.num_quads()) +
                               " quadrilateral cells (recombine needs triangles only)");
  for (const auto& p : m.nodes)
    if (!std::isfinite(p.x()) || !std::isfinite(p.y())) throw InputError(path, "non-finite node coordinate");
  for (int c = 0; c < m.num_cells(); ++c) {
    for (int i = 0; i < 3; ++i)
      if (m.cells[c].v[i] < 0 || m.cells[c].v[i] >= m.num_nodes())
        throw InputError(path, "cell " + number_text(c) + " refers to a missing node");
    if (!(cell_area(m, c) > 0))
      throw InputError(path, cell_label(m, c) + " is an inverted or degenerate triangle (area " +
                                 sci(cell_area(m, c)) + ")");
  }
  std::vector<EdgeNodes> fe;
  try {
    fe = free_edges(m);
  } catch (const InputError& e) {
    throw InputError(path, std::string(e.what()).substr(6));  // strip "mesh: "
  }
  std::unordered_map<std::uint64_t, char> isfree;
  for (const auto& e : fe) isfree[edge_key(e[0], e[1])] = 1;
  for (const auto& e : m.boundary)
    if (!isfree.count(edge_key(e.v[0], e.v[1])))
      throw InputError(path, "boundary edge between " + point_text(m.nodes[e.v[0]]) + " and " + point_text(m.nodes[e.v[1]]) +
                                 " is not a free edge of the triangulation");
}

}  // namespace quadapt
