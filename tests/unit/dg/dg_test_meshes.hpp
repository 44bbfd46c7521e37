#pragma once
// Test meshes for the DG solver: isotropic splitting of chosen quads into four (nested uniform
// refinement, and 2:1 non-conforming meshes with hanging nodes, e.g. a checkerboard split).
// A test helper only — the real refinement tool lives in lib/refine/.
#include <map>
#include <utility>
#include <vector>

#include "mesh/mesh.hpp"

namespace quadapt::dgtest {

/// Splits every quad c with flag[c] into four through its edge midpoints and its centre (the
/// bilinear map at (0, 0)). Midpoints are shared between flagged neighbours; boundary edges of
/// split cells are split too (same group). The caller keeps the result 2:1 (no neighbour of an
/// unsplit cell may be split twice). Cell order: unsplit cells keep their index order, children
/// follow their parent's position.
inline Mesh split_cells(const Mesh& in, const std::vector<char>& flag) {
  Mesh m = in;
  m.cells.clear();
  m.boundary.clear();
  m.clear_fields();
  std::map<std::pair<int, int>, int> mid;
  auto midpoint = [&](int a, int b) {
    auto k = a < b ? std::make_pair(a, b) : std::make_pair(b, a);
    auto it = mid.find(k);
    if (it != mid.end()) return it->second;
    m.nodes.push_back(0.5 * (in.nodes[a] + in.nodes[b]));
    int id = m.num_nodes() - 1;
    mid.emplace(k, id);
    return id;
  };
  for (int c = 0; c < in.num_cells(); ++c) {
    const Cell& cell = in.cells[c];
    if (!flag[c]) {
      m.cells.push_back(cell);
      continue;
    }
    int v[4], e[4];
    for (int k = 0; k < 4; ++k) v[k] = cell.v[k];
    for (int k = 0; k < 4; ++k) e[k] = midpoint(v[k], v[(k + 1) % 4]);
    m.nodes.push_back(map_to_physical(in, c, 0, 0));
    int ctr = m.num_nodes() - 1;
    // Children counter-clockwise, each with the parent's vertex k as its vertex k.
    Cell c0, c1, c2, c3;
    c0.v = {v[0], e[0], ctr, e[3]};
    c1.v = {e[0], v[1], e[1], ctr};
    c2.v = {ctr, e[1], v[2], e[2]};
    c3.v = {e[3], ctr, e[2], v[3]};
    for (const Cell& ch : {c0, c1, c2, c3}) m.cells.push_back(ch);
  }
  for (const BoundaryEdge& be : in.boundary) {
    auto k = be.v[0] < be.v[1] ? std::make_pair(be.v[0], be.v[1]) : std::make_pair(be.v[1], be.v[0]);
    auto it = mid.find(k);
    if (it == mid.end()) {
      m.boundary.push_back(be);
    } else {
      BoundaryEdge a = be, b = be;
      a.v = {be.v[0], it->second};
      b.v = {it->second, be.v[1]};
      m.boundary.push_back(a);
      m.boundary.push_back(b);
    }
  }
  return m;
}

/// Uniform (nested) refinement: every quad split into four.
inline Mesh refine_all(const Mesh& m) { return split_cells(m, std::vector<char>(m.cells.size(), 1)); }

/// Splits the cells whose centroid lies in an even square (i + j even) of an n-by-n
/// checkerboard of the unit square: on an n-by-n grid (perturbed or not) a 2:1 mesh with a
/// hanging node on every edge of every unsplit interior cell.
inline Mesh checkerboard_split(const Mesh& m, int n) {
  std::vector<char> flag(m.cells.size(), 0);
  for (int c = 0; c < m.num_cells(); ++c) {
    Vec2 x = cell_centroid(m, c);
    int i = static_cast<int>(x.x() * n), j = static_cast<int>(x.y() * n);
    flag[c] = (i + j) % 2 == 0;
  }
  return split_cells(m, flag);
}

/// Splits the cells whose centroid has x < 1/2: hanging nodes along one line, and midpoints
/// shared between split neighbours.
inline Mesh half_split(const Mesh& m) {
  std::vector<char> flag(m.cells.size(), 0);
  for (int c = 0; c < m.num_cells(); ++c) flag[c] = cell_centroid(m, c).x() < 0.5;
  return split_cells(m, flag);
}

}  // namespace quadapt::dgtest
