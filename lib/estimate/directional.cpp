#include "estimate/directional.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace quadapt {

namespace {
constexpr int kMaxDegree = 63;
// Σ a_i c^i s^(n-i) without allocation (n <= kMaxDegree).
inline double eval_cs(const std::vector<double>& a, double c, double s) {
  const int n = static_cast<int>(a.size()) - 1;
  double sp[kMaxDegree + 1];
  sp[0] = 1;
  for (int k = 1; k <= n; ++k) sp[k] = sp[k - 1] * s;
  double v = 0, ci = 1;
  for (int i = 0; i <= n; ++i) {
    v += a[i] * ci * sp[n - i];
    ci *= c;
  }
  return v;
}
}  // namespace

double directional_value(const std::vector<double>& a, double phi) {
  return eval_cs(a, std::cos(phi), std::sin(phi));
}

double directional_derivative(const std::vector<double>& a, double phi) {
  // d/dφ Σ a_i c^i s^(n-i) = Σ a_i [ -i c^(i-1) s^(n-i+1) + (n-i) c^(i+1) s^(n-i-1) ]
  const int n = static_cast<int>(a.size()) - 1;
  const double c = std::cos(phi), s = std::sin(phi);
  double cp[kMaxDegree + 2], sp[kMaxDegree + 2];
  cp[0] = sp[0] = 1;
  for (int k = 1; k <= n + 1; ++k) { cp[k] = cp[k - 1] * c; sp[k] = sp[k - 1] * s; }
  double v = 0;
  for (int i = 0; i <= n; ++i) {
    if (i > 0) v -= a[i] * i * cp[i - 1] * sp[n - i + 1];
    if (i < n) v += a[i] * (n - i) * cp[i + 1] * sp[n - i - 1];
  }
  return v;
}

DirectionalExtrema directional_extrema(const std::vector<double>& a) {
  DirectionalExtrema r;
  if (a.empty()) return r;
  double scale = 0;
  for (double v : a) scale = std::max(scale, std::abs(v));
  if (!(scale > 0) || !std::isfinite(scale)) return r;
  if (static_cast<int>(a.size()) - 1 > kMaxDegree) throw std::invalid_argument("directional_extrema: degree > 63");
  // |P| is a trigonometric polynomial of degree n on [0, π): 60 n samples put several in every
  // lobe, so the best sample brackets the global maximum
  const int N = std::max(120, 60 * (static_cast<int>(a.size()) - 1));
  const double dphi = M_PI / N;
  int best = 0;
  double bestv = -1;
  for (int k = 0; k < N; ++k) {
    const double v = std::abs(eval_cs(a, std::cos(k * dphi), std::sin(k * dphi)));
    if (v > bestv * (1 + 1e-12)) {
      bestv = v;
      best = k;
    }
  }
  // Refine: the maximum of |P| is a zero of g = sign(P) dP/dφ, which is > 0 before it and < 0
  // after it; bisect g on [φ_best - dφ, φ_best + dφ] to full precision (a golden-section search
  // on |P| itself would stall at sqrt(eps) in φ because the peak is flat).
  const double sgn = directional_value(a, best * dphi) < 0 ? -1.0 : 1.0;
  auto g = [&](double p) { return sgn * directional_derivative(a, p); };
  double lo = (best - 1) * dphi, hi = (best + 1) * dphi;
  double phi = best * dphi, A1 = bestv;
  if (g(lo) > 0 && g(hi) < 0) {
    for (int it = 0; it < 100 && hi - lo > 1e-15; ++it) {
      const double mid = 0.5 * (lo + hi);
      (g(mid) > 0 ? lo : hi) = mid;
    }
    const double cand = 0.5 * (lo + hi);
    const double v = std::abs(directional_value(a, cand));
    if (v >= A1 * (1 - 1e-14)) { phi = cand; A1 = std::max(A1, v); }
  }
  phi = std::fmod(phi, M_PI);
  if (phi < 0) phi += M_PI;
  if (phi >= M_PI - 1e-13) phi = 0;  // π ≡ 0
  r.A1 = A1;
  r.phi = phi;
  r.A2 = std::abs(directional_value(a, phi + 0.5 * M_PI));
  return r;
}

}  // namespace quadapt
