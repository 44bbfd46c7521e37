// The Gmsh interpolation matrices reproduce the tensor GLL Lagrange basis of lib/fem/basis.hpp.
#include <doctest/doctest.h>

#include <cmath>

#include "fem/basis.hpp"
#include "io/gll_scheme.hpp"
#include "../worst.hpp"

using namespace quadapt;

TEST_CASE("coef * monomials = l_i(xi) l_j(eta), k = i + (p+1) j") {
  for (int p = 1; p <= 8; ++p) {
    CAPTURE(p);
    const GmshInterpolation g = gll_interpolation(p);
    REQUIRE(g.n == (p + 1) * (p + 1));
    LagrangeBasis1D b(p);
    double err = 0;
    for (double xi : {-1.0, -0.93, -0.3, 0.1, 0.77, 1.0})
      for (double eta : {-1.0, -0.81, 0.2, 0.95}) {
        Eigen::VectorXd lx = b.eval(xi), ly = b.eval(eta);
        for (int k = 0; k < g.n; ++k) {
          double s = 0;
          for (int m = 0; m < g.n; ++m)
            s += g.coef[k * g.n + m] * std::pow(xi, g.exp[3 * m]) * std::pow(eta, g.exp[3 * m + 1]);
          err = quadapt_test::worst_of(err, std::abs(s - lx[k % (p + 1)] * ly[k / (p + 1)]));
        }
      }
    CHECK(err < 1e-12);
  }
  // p = 0: the constant
  const GmshInterpolation g0 = gll_interpolation(0);
  CHECK(g0.n == 1);
  CHECK(g0.coef[0] == 1.0);
}

TEST_CASE("scheme names") {
  CHECK(gll_scheme_name(3) == "quadapt_gll_p3");
  CHECK(parse_gll_scheme_name("quadapt_gll_p3") == 3);
  CHECK(parse_gll_scheme_name("quadapt_gll_p12") == 12);
  CHECK(parse_gll_scheme_name("INTERPOLATION_SCHEME") == -1);
  CHECK(parse_gll_scheme_name("quadapt_gll_p") == -1);
  CHECK(parse_gll_scheme_name("quadapt_gll_p2x") == -1);
}
