#include "estimate/polynomial_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "estimate/error_model.hpp"

namespace quadapt {

namespace {

constexpr int kLogRhoSteps = 32;
constexpr double kTolerance = 1e-9;

// G_m = ∫_0^{2π} cos^m sin^(2n-m) dφ = 2π (m-1)!! (2n-m-1)!! / (2n)!! for even m, (-1)!! = 1.
double angular_moment(int m, int n) {
  double r = 2 * M_PI;
  for (int k = m - 1; k > 0; k -= 2) r *= k;
  for (int k = 2 * n - m - 1; k > 0; k -= 2) r *= k;
  for (int k = 2 * n; k > 0; k -= 2) r /= k;
  return r;
}

// I(θ, ρ) for one polynomial: for q = 2 the closed form in ρ, with the θ-dependent sums cached
// for the last θ; otherwise a uniform rule over φ (|P|^q is π-periodic).
class ShapeIntegral {
 public:
  ShapeIntegral(const std::vector<double>& a, double q) : a_(a), n_(static_cast<int>(a.size()) - 1), q_(q) {
    G_.resize(n_ + 1);
    for (int j = 0; j <= n_; ++j) G_[j] = angular_moment(2 * j, n_);
    b_.resize(n_ + 1);
    C_.resize(n_ + 1);
    xp_.resize(n_ + 1);
    yp_.resize(n_ + 1);
  }

  /// The coefficients of ρ^(2j-n) in I(θ, ρ) for q = 2.
  const std::vector<double>& coefficients(double theta) {
    if (theta != cached_theta_) {
      rotate(theta);
      for (int j = 0; j <= n_; ++j) {
        double s = 0;
        for (int k = std::max(0, 2 * j - n_); k <= std::min(n_, 2 * j); ++k) s += b_[k] * b_[2 * j - k];
        C_[j] = G_[j] * s;
      }
      cached_theta_ = theta;
    }
    return C_;
  }

  double value(double theta, double t) { return q_ == 2 ? value2(theta, t) : value_q(theta, t); }

  /// I for q = 2 (closed form).
  double value2(double theta, double t) {
    const std::vector<double>& C = coefficients(theta);
    const double r2 = std::exp(2 * t);
    double rj = std::exp(-n_ * t), s = 0;
    for (int j = 0; j <= n_; ++j, rj *= r2) s += C[j] * rj;
    return std::max(0.0, s);
  }

  /// I for any q: the uniform rule on 64 + 8n directions over [0, π), doubled.
  double value_q(double theta, double t) {
    const int N = 64 + 8 * n_;
    const double c = std::cos(theta), s = std::sin(theta), sr = std::exp(0.5 * t);
    double sum = 0;
    for (int k = 0; k < N; ++k) {
      const double ph = M_PI * k / N;
      const double x1 = sr * std::cos(ph), x2 = std::sin(ph) / sr;
      sum += std::pow(std::abs(evaluate(c * x1 - s * x2, s * x1 + c * x2)), q_);
    }
    return 2 * M_PI * sum / N;
  }

  int degree() const { return n_; }

 private:
  double evaluate(double x, double y) {
    yp_[0] = 1;
    for (int j = 1; j <= n_; ++j) yp_[j] = yp_[j - 1] * y;
    double v = 0, xi = 1;
    for (int i = 0; i <= n_; ++i, xi *= x) v += a_[i] * xi * yp_[n_ - i];
    return v;
  }

  // b_k: P(c ξ1 - s ξ2, s ξ1 + c ξ2) = Σ b_k ξ1^k ξ2^(n-k), by products of the linear forms
  void rotate(double theta) {
    const double c = std::cos(theta), s = std::sin(theta);
    auto times = [](std::vector<double>& poly, int deg, double alpha, double beta) {
      // poly (degree deg, index = power of ξ1) times (alpha ξ1 + beta ξ2) -> degree deg + 1
      poly[deg + 1] = alpha * poly[deg];
      for (int k = deg; k >= 1; --k) poly[k] = alpha * poly[k - 1] + beta * poly[k];
      poly[0] = beta * poly[0];
    };
    std::fill(b_.begin(), b_.end(), 0.0);
    for (int i = 0; i <= n_; ++i) {
      if (a_[i] == 0) continue;
      // x^i y^(n-i) with x = (c, -s), y = (s, c)
      std::fill(xp_.begin(), xp_.end(), 0.0);
      xp_[0] = 1;
      int deg = 0;
      for (int k = 0; k < i; ++k, ++deg) times(xp_, deg, c, -s);
      for (int k = 0; k < n_ - i; ++k, ++deg) times(xp_, deg, s, c);
      for (int k = 0; k <= n_; ++k) b_[k] += a_[i] * xp_[k];
    }
  }

  const std::vector<double>& a_;
  int n_;
  double q_;
  std::vector<double> G_, b_, C_, xp_, yp_;
  double cached_theta_ = std::nan("");
};

// the result from the minimiser (θ, t = log ρ) and the minimum of the scaled polynomial
PolynomialShape finish(double theta, double t, double best, double scale, double q, int n) {
  PolynomialShape r;
  r.theta = wrap_pi(theta);
  r.rho = std::exp(t);
  r.I = best * std::pow(scale, q);
  const double root = std::pow(best / (2 * M_PI), 1 / q) * scale;  // sqrt(A1 A2)
  const double half = std::pow(r.rho, 0.5 * n);
  r.A1 = root * half;
  r.A2 = root / half;
  r.phi = wrap_pi(r.theta + 0.5 * M_PI);
  return r;
}

}  // namespace

double polynomial_shape_integral(const std::vector<double>& a, double theta, double rho, double q) {
  ShapeIntegral f(a, q);
  return f.value(theta, std::log(rho));
}

PolynomialShape polynomial_stretch(const std::vector<double>& a, double q, double rho_max, double theta) {
  double scale = 0;
  for (double v : a) scale = std::max(scale, std::abs(v));
  if (a.size() < 2 || !(scale > 0) || !std::isfinite(scale)) {
    PolynomialShape r;
    r.theta = wrap_pi(theta);
    r.phi = wrap_pi(theta + 0.5 * M_PI);
    return r;
  }
  std::vector<double> u(a);
  for (double& v : u) v /= scale;
  ShapeIntegral f(u, q);
  const double T = rho_max > 1 ? std::log(rho_max) : 0.0;
  // grid in log ρ, then golden-section search on the bracket around the best grid point
  double best = std::numeric_limits<double>::infinity(), bs = 0;
  int bk = 0;
  for (int k = 0; k <= kLogRhoSteps; ++k) {
    const double t = T * k / kLogRhoSteps;
    const double v = f.value(theta, t);
    if (v < best) { best = v; bs = t; bk = k; }
  }
  double lo = T * std::max(0, bk - 1) / kLogRhoSteps, hi = T * std::min(kLogRhoSteps, bk + 1) / kLogRhoSteps;
  const double g = 0.5 * (std::sqrt(5.0) - 1);
  double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
  double f1 = f.value(theta, x1), f2 = f.value(theta, x2);
  while (hi - lo > kTolerance) {
    if (f1 <= f2) { hi = x2; x2 = x1; f2 = f1; x1 = hi - g * (hi - lo); f1 = f.value(theta, x1); }
    else { lo = x1; x1 = x2; f1 = f2; x2 = lo + g * (hi - lo); f2 = f.value(theta, x2); }
  }
  for (double t : {x1, x2})
    if (const double v = f.value(theta, t); v < best) { best = v; bs = t; }
  return finish(theta, bs, best, scale, q, f.degree());
}

}  // namespace quadapt
