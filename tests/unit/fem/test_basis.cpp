#include <doctest/doctest.h>

#include <cmath>

#include "fem/basis.hpp"

using namespace quadapt;

TEST_CASE("Gauss-Legendre and Gauss-Lobatto integrate polynomials exactly") {
  for (int n = 1; n <= 8; ++n) {
    Rule1D g = gauss_legendre(n);
    for (int k = 0; k <= 2 * n - 1; ++k) {
      double s = 0;
      for (int i = 0; i < n; ++i) s += g.w[i] * std::pow(g.x[i], k);
      double exact = (k % 2) ? 0.0 : 2.0 / (k + 1);
      CHECK(s == doctest::Approx(exact).epsilon(1e-13));
    }
  }
  for (int n = 2; n <= 8; ++n) {
    Rule1D g = gauss_lobatto(n);
    CHECK(g.x.front() == -1.0);
    CHECK(g.x.back() == 1.0);
    for (int k = 0; k <= 2 * n - 3; ++k) {
      double s = 0;
      for (int i = 0; i < n; ++i) s += g.w[i] * std::pow(g.x[i], k);
      double exact = (k % 2) ? 0.0 : 2.0 / (k + 1);
      CHECK(s == doctest::Approx(exact).epsilon(1e-13));
    }
  }
}

TEST_CASE("Lagrange basis: Kronecker property, partition of unity, derivative by FD") {
  for (int p = 1; p <= 5; ++p) {
    LagrangeBasis1D b(p);
    for (int i = 0; i <= p; ++i) {
      Eigen::VectorXd l = b.eval(b.nodes()[i]);
      for (int j = 0; j <= p; ++j) CHECK(l[j] == doctest::Approx(i == j ? 1.0 : 0.0));
    }
    for (double x : {-0.9, -0.3, 0.1, 0.77}) {
      CHECK(b.eval(x).sum() == doctest::Approx(1.0).epsilon(1e-13));
      CHECK(std::abs(b.deriv(x).sum()) < 1e-11);
      const double h = 1e-6;
      Eigen::VectorXd fd = (b.eval(x + h) - b.eval(x - h)) / (2 * h);
      CHECK((fd - b.deriv(x)).norm() < 1e-7);
    }
  }
}
