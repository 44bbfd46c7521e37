#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "estimate/directional.hpp"
#include "estimate/error_model.hpp"
#include "test_util.hpp"

using namespace quadapt;
using quadapt::testutil::angle_diff_mod_pi;
using quadapt::testutil::binom;

namespace {
// Coefficients (a[i] of x^i y^(n-i)) of c1 s^n + c2 t^n with s = x cos a + y sin a,
// t = -x sin a + y cos a: by binomial expansion.
std::vector<double> rotated(int n, double c1, double c2, double ang) {
  std::vector<double> a(n + 1, 0.0);
  const double c = std::cos(ang), s = std::sin(ang);
  for (int i = 0; i <= n; ++i) {
    a[i] += c1 * binom(n, i) * std::pow(c, i) * std::pow(s, n - i);
    a[i] += c2 * binom(n, i) * std::pow(-s, i) * std::pow(c, n - i);
  }
  return a;
}
}  // namespace

TEST_CASE("directional extrema: hand values") {
  // x^n: A1 = 1 along x, nothing across
  for (int n = 2; n <= 5; ++n) {
    std::vector<double> a(n + 1, 0.0);
    a[n] = 1;
    auto d = directional_extrema(a);
    CHECK(d.A1 == doctest::Approx(1).epsilon(1e-12));
    CHECK(d.A2 == doctest::Approx(0).epsilon(1e-12));
    CHECK(angle_diff_mod_pi(d.phi, 0) < 1e-9);
  }
  // n = 2: 3 s^2 - t^2 -> A1 = 3 along s, A2 = 1
  // n = 3: 2 s^3 + t^3 -> A1 = 2 along s, A2 = 1 (the interior critical value is 2/sqrt5)
  // n = 4: s^4 + 0.5 t^4 -> A1 = 1 along s, A2 = 0.5
  struct Case { int n; double c1, c2, A1, A2; };
  for (Case k : {Case{2, 3, -1, 3, 1}, Case{3, 2, 1, 2, 1}, Case{4, 1, 0.5, 1, 0.5}, Case{3, -2, 1, 2, 1}})
    for (double ang : {0.0, 0.3, 1.0, 2.0, 2.9}) {
      CAPTURE(k.n);
      CAPTURE(ang);
      auto d = directional_extrema(rotated(k.n, k.c1, k.c2, ang));
      CHECK(d.A1 == doctest::Approx(k.A1).epsilon(1e-12));
      CHECK(d.A2 == doctest::Approx(k.A2).epsilon(1e-9));
      CHECK(angle_diff_mod_pi(d.phi, ang) < 1e-7);
      CHECK(d.phi >= 0);
      CHECK(d.phi < M_PI);
    }
  // zero polynomial: all zero, no NaN
  auto z = directional_extrema(std::vector<double>(4, 0.0));
  CHECK(z.A1 == 0);
  CHECK(z.A2 == 0);
  CHECK(z.phi == 0);
}

TEST_CASE("optimal shape: thin along the largest derivative, long axis theta = phi - pi/2") {
  // A1 along x (phi = 0), A2 = A1/16 with n = 2: h_along/h_across = (1/16)^(1/2) = 1/4
  FrameShape s = optimal_shape(16, 1, 0.0, 2, 2, 1e6);
  CHECK(s.rho == doctest::Approx(4));
  CHECK(angle_diff_mod_pi(s.theta, M_PI / 2) < 1e-14);  // long axis along y
  // vanishing A2: capped, finite, B > 0
  FrameShape c = optimal_shape(1, 0, 0.4, 3, 2, 25);
  CHECK(c.rho == doctest::Approx(25));
  CHECK(std::isfinite(c.B));
  CHECK(c.B > 0);
  CHECK(c.B == doctest::Approx(error_constant(1, std::pow(25.0, -3), 3, 2)));
  // vanishing A1: isotropic, B = 0
  FrameShape z = optimal_shape(0, 0, 1.0, 3, 2, 25);
  CHECK(z.rho == 1);
  CHECK(z.theta == 0);
  CHECK(z.B == 0);
}

TEST_CASE("error constant B: quadrature of the bound (5.9) over the circumscribed ellipse") {
  // e per unit area = (1/area) * ∫_Σ (y^T Q y)^(q n/2) dy with Σ the ellipse through the corners
  // of the optimal element (half-axes h_along, h_across), area = 4 h^2 = 1/d.
  for (int n : {2, 3, 4})
    for (double q : {1.0, 2.0, 3.0}) {
      CAPTURE(n);
      CAPTURE(q);
      const double A1 = 7.0, A2 = 0.3, phi = 0.8, h = 0.05;
      const double ha = h * std::pow(A2 / A1, 0.5 / n), hc = h * std::pow(A1 / A2, 0.5 / n);
      const double d = 1 / (4 * h * h);
      // polar quadrature in the ellipse's own coordinates: y = R(phi) (sqrt2 ha r cos t, sqrt2 hc r sin t)
      const int NR = 400, NT = 400;
      double sum = 0;
      for (int i = 0; i < NR; ++i)
        for (int j = 0; j < NT; ++j) {
          const double r = (i + 0.5) / NR, t = 2 * M_PI * (j + 0.5) / NT;
          const double s = std::sqrt(2.0) * ha * r * std::cos(t), u = std::sqrt(2.0) * hc * r * std::sin(t);
          const double Qyy = std::pow(A1, 2.0 / n) * s * s + std::pow(A2, 2.0 / n) * u * u;
          sum += std::pow(Qyy, q * n / 2.0) * r * (1.0 / NR) * (2 * M_PI / NT) * 2 * ha * hc;
        }
      (void)phi;  // the bound is rotation invariant in its own frame
      const double e = sum * d;
      CHECK(e == doctest::Approx(error_constant(A1, A2, n, q) * std::pow(d, -q * n / 2.0)).epsilon(1e-4));
    }
}
