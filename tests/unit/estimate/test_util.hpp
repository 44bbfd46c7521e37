#pragma once
// Helpers shared by the estimate/sizing unit tests (in-memory meshes and DG fields).
#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "mesh/mesh.hpp"

namespace quadapt::testutil {

/// |a - b| as undirected angles: in [0, π/2].
inline double angle_diff_mod_pi(double a, double b) {
  double d = std::fmod(std::abs(a - b), M_PI);
  return std::min(d, M_PI - d);
}

/// The binomial coefficient C(n, k) as a double.
inline double binom(int n, int k) {
  double r = 1;
  for (int i = 1; i <= k; ++i) r = r * (n - k + i) / i;
  return r;
}

/// Maps the unit-square mesh m affinely onto [x0,x1] x [y0,y1].
inline Mesh rescale(Mesh m, double x0, double x1, double y0, double y1) {
  for (auto& p : m.nodes) p = Vec2(x0 + (x1 - x0) * p.x(), y0 + (y1 - y0) * p.y());
  return m;
}

/// Splits the listed quads into 4 (mid-edge and centre nodes), leaving their neighbours
/// unsplit: a 2:1 non-conforming (hanging-node) mesh. Boundary edges are not updated (the
/// estimator does not use them).
inline Mesh split_cells(const Mesh& in, const std::vector<int>& which) {
  Mesh m = in;
  std::map<std::pair<int, int>, int> mid;
  auto midpoint = [&](int a, int b) {
    auto key = std::make_pair(std::min(a, b), std::max(a, b));
    auto it = mid.find(key);
    if (it != mid.end()) return it->second;
    m.nodes.push_back(0.5 * (m.nodes[a] + m.nodes[b]));
    int id = m.num_nodes() - 1;
    mid[key] = id;
    return id;
  };
  std::vector<bool> split(in.cells.size(), false);
  for (int c : which) split[c] = true;
  std::vector<Cell> cells;
  for (int c = 0; c < in.num_cells(); ++c) {
    const Cell& q = in.cells[c];
    if (!split[c]) { cells.push_back(q); continue; }
    int v0 = q.v[0], v1 = q.v[1], v2 = q.v[2], v3 = q.v[3];
    int m01 = midpoint(v0, v1), m12 = midpoint(v1, v2), m23 = midpoint(v2, v3), m30 = midpoint(v3, v0);
    m.nodes.push_back(0.25 * (in.nodes[v0] + in.nodes[v1] + in.nodes[v2] + in.nodes[v3]));
    int cc = m.num_nodes() - 1;
    Cell a; a.v = {{v0, m01, cc, m30}};
    Cell b; b.v = {{m01, v1, m12, cc}};
    Cell d; d.v = {{cc, m12, v2, m23}};
    Cell e; e.v = {{m30, cc, m23, v3}};
    cells.insert(cells.end(), {a, b, d, e});
  }
  m.cells = cells;
  m.boundary.clear();
  m.clear_fields();
  return m;
}

}  // namespace quadapt::testutil
