#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "core/error.hpp"
#include "estimate/interpolate.hpp"
#include "estimate/reconstruct.hpp"
#include "mesh/topology.hpp"
#include "test_util.hpp"
#include "../worst.hpp"

using namespace quadapt;

namespace {
// A random polynomial of total degree n with O(1) coefficients.
struct Poly {
  int n;
  std::vector<std::pair<int, int>> e;
  std::vector<double> c;
  Poly(int n_, unsigned seed) : n(n_), e(monomial_exponents(n_)) {
    std::mt19937 g(seed);
    std::uniform_real_distribution<double> d(-1, 1);
    for (size_t k = 0; k < e.size(); ++k) c.push_back(d(g));
  }
  double operator()(double x, double y) const {
    double v = 0;
    for (size_t k = 0; k < e.size(); ++k) v += c[k] * std::pow(x - 0.3, e[k].first) * std::pow(y - 0.6, e[k].second);
    return v;
  }
};

void check_exact(const Mesh& m, int p, int n, unsigned seed) {
  Poly u(n, seed);
  CellNodeField f = interpolate_dg(m, p, [&](double x, double y) { return u(x, y); });
  PatchReconstructor rec(m, f.values, p, n);
  Topology t = build_topology(m);
  double maxerr = 0, maxtop = 0;
  for (int c = 0; c < m.num_cells(); ++c) {
    auto patch = t.neighbours(c);
    patch.insert(patch.begin(), c);
    PatchPolynomial r = rec.reconstruct(c, patch);
    for (int k = 0; k < m.cells[c].nv; ++k) {
      const Vec2 x = m.nodes[m.cells[c].v[k]];
      maxerr = quadapt_test::worst_of(maxerr, std::abs(r.eval(x) - u(x.x(), x.y())));
    }
    // the top homogeneous part is the degree-n coefficients of u (translation invariant)
    auto a = r.top_homogeneous();
    for (size_t k = 0; k < u.e.size(); ++k)
      if (u.e[k].first + u.e[k].second == n) maxtop = quadapt_test::worst_of(maxtop, std::abs(a[u.e[k].first] - u.c[k]));
  }
  CHECK(maxerr < 1e-9);
  CHECK(maxtop < 1e-6);
}
}  // namespace

TEST_CASE("H1 patch reconstruction reproduces P^n exactly (structured, perturbed, hanging nodes)") {
  for (int n = 2; n <= 4; ++n) {
    CAPTURE(n);
    // a degree-n DG field contains P^n: the reconstruction must return it exactly
    check_exact(make_structured_quads(6, 5), n, n, 11 + n);
    check_exact(make_perturbed_quads(6, 6, 0.3, 7), n, n, 21 + n);
    check_exact(testutil::split_cells(make_perturbed_quads(5, 5, 0.2, 3), {6, 12, 18}), n, n, 31 + n);
  }
}

TEST_CASE("degree-p field holding a polynomial of P^{p+1} ∩ Q_p: degree-(p+1) reconstruction is exact") {
  // x^p y and x y^p have total degree p+1 and lie in the tensor space Q_p.
  for (int p = 1; p <= 3; ++p) {
    CAPTURE(p);
    auto u = [p](double x, double y) {
      return 0.7 * std::pow(x, p) * y - 1.3 * x * std::pow(y, p) + 0.5 * x * y + 2 * x - y + 1;
    };
    // axis-aligned rectangles of varying size: Q_p holds x^p y exactly (bilinear or sheared
    // cells would not)
    Mesh m = make_structured_quads(5, 5);
    for (auto& x : m.nodes) x = Vec2(x.x() + 0.3 * x.x() * x.x() - 0.1, 0.8 * x.y() - 0.2 * x.y() * x.y() + 0.3);
    CellNodeField f = interpolate_dg(m, p, u);
    PatchReconstructor rec(m, f.values, p, p + 1);
    Topology t = build_topology(m);
    for (int c : {0, 7, 12, 24}) {
      auto patch = t.neighbours(c);
      patch.insert(patch.begin(), c);
      PatchPolynomial r = rec.reconstruct(c, patch);
      auto a = r.top_homogeneous();  // a[i] multiplies x^i y^(p+1-i)
      std::vector<double> expect(p + 2, 0.0);
      expect[p] += 0.7;   // x^p y
      expect[1] += -1.3;  // x y^p
      if (p == 1) { expect[1] = 0.7 - 1.3 + 0.5; }  // x y collects all three terms
      for (int i = 0; i <= p + 1; ++i) CHECK(a[i] == doctest::Approx(expect[i]).epsilon(1e-8));
      CHECK(r.eval(cell_centroid(m, c)) == doctest::Approx(u(cell_centroid(m, c).x(), cell_centroid(m, c).y())).epsilon(1e-10));
    }
  }
}

TEST_CASE("reconstruction input checks") {
  Mesh m = make_structured_quads(2, 2);
  std::vector<double> wrong(3, 0.0);
  CHECK_THROWS_AS(PatchReconstructor(m, wrong, 2, 3), InputError);
}
