#include "lpcvt/phases.hpp"

#include <algorithm>
#include <cmath>

#include "frame/frame.hpp"
#include "quad/recombine.hpp"
#include "quality/mesh_quality.hpp"

namespace quadapt::lpcvt {

Vec2 phase_offset(int k, int K) {
  if (K <= 1) return Vec2::Zero();
  // generator a: the integer nearest K / golden ratio, made coprime with K (then k a mod K runs
  // over every residue, so each axis alone gets K distinct phases)
  auto gcd = [](int x, int y) {
    while (y) {
      const int t = x % y;
      x = y;
      y = t;
    }
    return x;
  };
  int a = std::max(1, static_cast<int>(std::lround(K * 0.6180339887498949)));
  while (gcd(a, K) != 1) ++a;
  return Vec2(static_cast<double>(k % K) / K, static_cast<double>((static_cast<long>(k) * a) % K) / K);
}

bool PhaseScore::better_than(const PhaseScore& o) const {
  if (irregular != o.irregular) return irregular < o.irregular;
  return quality > o.quality + 1e-12;
}

PhaseScore recombine_score(const Mesh& tri) {
  RecombineOptions opt;
  opt.matching = RecombineOptions::Matching::Metric;
  opt.frame = frame_from_mesh(tri, "lpcvt output").oriented();
  RecombineStats st;
  const Mesh q = recombine_to_all_quads(tri, opt, &st, "lpcvt output");
  PhaseScore s;
  vertex_regularity(q, s.interior, s.irregular);
  s.unmatched = st.metric.triangles;
  s.quality = st.metric.mean_quality;
  return s;
}

}  // namespace quadapt::lpcvt
