#include "fem/quadrature.hpp"

#include <cmath>
#include <map>
#include <mutex>

#include "fem/basis.hpp"

namespace quadapt {

const TriangleRule& dunavant6() {
  static const TriangleRule rule = [] {
    TriangleRule r;
    r.degree = 6;
    auto orbit3 = [&](double a, double b, double w) {  // (a, b, b) and permutations
      r.bary.push_back({a, b, b});
      r.bary.push_back({b, a, b});
      r.bary.push_back({b, b, a});
      for (int k = 0; k < 3; ++k) r.w.push_back(w);
    };
    auto orbit6 = [&](double a, double b, double c, double w) {
      const double p[6][3] = {{a, b, c}, {a, c, b}, {b, a, c}, {b, c, a}, {c, a, b}, {c, b, a}};
      for (auto& q : p) {
        r.bary.push_back({q[0], q[1], q[2]});
        r.w.push_back(w);
      }
    };
    orbit3(0.501426509658179, 0.249286745170910, 0.116786275726379);
    orbit3(0.873821971016996, 0.063089014491502, 0.050844906370207);
    orbit6(0.053145049844817, 0.310352451033784, 0.636502499121399, 0.082851075618374);
    // Normalise the weights exactly to 1 (the tabulated values carry 15 digits).
    double s = 0;
    for (double w : r.w) s += w;
    for (double& w : r.w) w /= s;
    return r;
  }();
  return rule;
}

TriangleRule collapsed_gauss(int degree) {
  if (degree < 0) degree = 0;
  // Map (u, v) in [0,1]^2 to (s, t) = (u, v (1 - u)), Jacobian (1 - u): a degree-d polynomial
  // in (s, t) becomes degree <= d+1 in u and <= d in v.
  const int nu = (degree + 2 + 1) / 2, nv = (degree + 1 + 1) / 2;
  Rule1D gu = gauss_legendre(std::max(1, nu)), gv = gauss_legendre(std::max(1, nv));
  TriangleRule r;
  r.degree = degree;
  for (size_t i = 0; i < gu.x.size(); ++i) {
    double u = 0.5 * (gu.x[i] + 1), wu = 0.5 * gu.w[i];
    for (size_t j = 0; j < gv.x.size(); ++j) {
      double v = 0.5 * (gv.x[j] + 1), wv = 0.5 * gv.w[j];
      double s = u, t = v * (1 - u);
      r.bary.push_back({1 - s - t, s, t});
      r.w.push_back(2 * wu * wv * (1 - u));  // reference area 1/2 -> weights sum to 1
    }
  }
  return r;
}

const TriangleRule& rule_for_exponent(double p) {
  if (p <= 6) return dunavant6();
  static std::mutex mu;
  static std::map<int, TriangleRule> cache;
  std::lock_guard<std::mutex> lock(mu);
  int d = static_cast<int>(std::ceil(p));
  auto it = cache.find(d);
  if (it == cache.end()) it = cache.emplace(d, collapsed_gauss(d)).first;
  return it->second;
}

}  // namespace quadapt
