#include "lpcvt/seed.hpp"

#include <algorithm>
#include <cmath>
#include <random>

namespace quadapt::lpcvt {

namespace {
double tri_area(const Vec2& a, const Vec2& b, const Vec2& c) {
  return 0.5 * ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
}
}  // namespace

std::vector<Vec2> seed_points(const Background& bg, int n, SeedMode mode, unsigned seed) {
  std::vector<Vec2> out;
  if (n <= 0) return out;
  // one entry per triangle of every integration cell
  struct Tri {
    Vec2 a, b, c;
  };
  std::vector<Tri> tris;
  std::vector<double> cum;
  double total = 0;
  for (int q = 0; q < bg.num_cells(); ++q) {
    const IntegrationCell& ic = bg.cell(q);
    for (int t = 1; t + 1 < ic.nv; ++t) {
      Tri tr{ic.v[0], ic.v[t], ic.v[t + 1]};
      double w = tri_area(tr.a, tr.b, tr.c);
      if (mode == SeedMode::Density) w *= std::abs(bg.metric(q, (tr.a + tr.b + tr.c) / 3).determinant());
      total += w;
      tris.push_back(tr);
      cum.push_back(total);
    }
  }
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  out.reserve(n);
  while (static_cast<int>(out.size()) < n) {
    double r = u01(rng) * total;
    size_t k = std::min<size_t>(std::upper_bound(cum.begin(), cum.end(), r) - cum.begin(), tris.size() - 1);
    double s = u01(rng), t = u01(rng);
    if (s + t > 1) {
      s = 1 - s;
      t = 1 - t;
    }
    if (s <= 0 || t <= 0 || s + t >= 1) continue;  // strictly inside
    const Tri& tr = tris[k];
    out.push_back(tr.a + s * (tr.b - tr.a) + t * (tr.c - tr.a));
  }
  return out;
}

}  // namespace quadapt::lpcvt
