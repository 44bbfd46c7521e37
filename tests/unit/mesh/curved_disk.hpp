#pragma once
// Test mesh: the disk of radius R as 5 patches (a central square of half-width R/2 and four
// rings), n x n cells each, curved cells of order q whose control points are the exact images
// of the equispaced reference points under the patch maps (so every boundary control point lies
// on the circle). Boundary group "circle".
#include <cmath>
#include <map>
#include <utility>

#include "mesh/mesh.hpp"

namespace quadapt::curvedtest {

inline Mesh curved_disk(int n, int q, double R = 1.0) {
  const double a = 0.5 * R;
  Mesh m;
  m.curved.order = q;
  std::map<std::pair<long long, long long>, int> node_of;
  auto vertex = [&](const Vec2& x) {
    auto k = std::make_pair(std::llround(x.x() * 1e9), std::llround(x.y() * 1e9));
    auto it = node_of.find(k);
    if (it != node_of.end()) return it->second;
    m.nodes.push_back(x);
    node_of.emplace(k, m.num_nodes() - 1);
    return m.num_nodes() - 1;
  };
  // Patch maps on (u, w) in [0, 1]^2 (u: first reference direction, w: second).
  auto patch = [&](int k, double u, double w) -> Vec2 {
    if (k == 4) return Vec2(a * (2 * u - 1), a * (2 * w - 1));  // centre
    const double s = 2 * w - 1, t = u;                          // along the side, outward
    const Vec2 inner(a, a * s), outer(R * std::cos(M_PI / 4 * s), R * std::sin(M_PI / 4 * s));
    const Vec2 x = (1 - t) * inner + t * outer;
    const double c = std::cos(k * M_PI / 2), sn = std::sin(k * M_PI / 2);
    return Vec2(c * x.x() - sn * x.y(), sn * x.x() + c * x.y());
  };
  m.groups = {{1, "circle"}};
  m.domain_tag = 2;
  for (int k = 0; k < 5; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const size_t base = m.curved.points.size();
        for (int b = 0; b <= q; ++b)
          for (int c = 0; c <= q; ++c)
            m.curved.points.push_back(patch(k, (i + double(c) / q) / n, (j + double(b) / q) / n));
        Cell cell;
        const int corner[4] = {0, q, q + (q + 1) * q, (q + 1) * q};
        for (int v = 0; v < 4; ++v) {
          cell.v[v] = vertex(m.curved.points[base + corner[v]]);
          m.curved.points[base + corner[v]] = m.nodes[cell.v[v]];
        }
        m.cells.push_back(cell);
        if (k < 4 && i == n - 1) m.boundary.push_back({{cell.v[1], cell.v[2]}, 0});
      }
  if (q == 1) m.curved = CurvedGeometry{};  // straight: the vertices say it all
  return m;
}

}  // namespace quadapt::curvedtest
