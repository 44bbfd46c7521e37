#include "quad/boundary_corners.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace quadapt {

BoundaryCornerStats split_flat_boundary_corners(Mesh& m, double max_angle_deg) {
  BoundaryCornerStats st;
  const double max_angle = max_angle_deg * M_PI / 180;
  // cells per vertex (a boundary vertex with one cell: its two edges there are boundary edges)
  std::vector<int> valence(m.nodes.size(), 0), only_cell(m.nodes.size(), -1);
  for (int c = 0; c < m.num_cells(); ++c)
    for (int k = 0; k < m.cells[c].nv; ++k) {
      ++valence[m.cells[c].v[k]];
      only_cell[m.cells[c].v[k]] = c;
    }
  // the angle at node v between the directions to x and y, and whether (i, j, l) turns left
  auto angle = [&](int v, int x, int y) {
    const Vec2 u = m.nodes[x] - m.nodes[v], w = m.nodes[y] - m.nodes[v];
    return std::acos(std::clamp(u.dot(w) / (u.norm() * w.norm()), -1.0, 1.0));
  };
  auto ccw = [&](int i, int j, int l) {
    const Vec2 u = m.nodes[j] - m.nodes[i], w = m.nodes[l] - m.nodes[i];
    return u.x() * w.y() - u.y() * w.x() > 0;
  };
  std::vector<char> done(m.num_cells(), 0);
  for (int v = 0; v < static_cast<int>(m.nodes.size()); ++v) {
    if (valence[v] != 1) continue;
    const int qc = only_cell[v];
    const Cell Q = m.cells[qc];
    const int k = static_cast<int>(std::find(Q.v.begin(), Q.v.begin() + Q.nv, v) - Q.v.begin());
    const int b = Q.v[(k + 1) % Q.nv], a = Q.v[(k + Q.nv - 1) % Q.nv];
    if (!(angle(v, b, a) > max_angle)) continue;
    ++st.flat_vertices;
    if (!Q.is_quad() || done[qc]) continue;  // a quad with two flat corners is split once
    const int c = Q.v[(k + 2) % 4];
    // both triangles strictly counter-clockwise (a convex quad's diagonal; a reflex one's may not be)
    if (!ccw(v, b, c) || !ccw(v, c, a)) continue;
    // the split must open the corner: both new angles at v below the bound (a skewed quad whose
    // diagonal v-c runs along one of v's edges would keep ~the old angle in one triangle)
    if (angle(v, b, c) > max_angle || angle(v, c, a) > max_angle) continue;
    Cell t1, t2;
    t1.nv = t2.nv = 3;
    t1.v = {v, b, c, -1};
    t2.v = {v, c, a, -1};
    m.cells[qc] = t1;
    m.cells.push_back(t2);
    done[qc] = 1;
    ++st.split;
  }
  return st;
}

}  // namespace quadapt
