// L_p-CVT energy (eq. 4.1) and its analytic gradient (eqs. 4.8-4.11) against exact integrals
// and central finite differences.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <string>

#include "helpers.hpp"
#include "lpcvt/boundary_points.hpp"
#include "lpcvt/energy.hpp"
#include "fem/quadrature.hpp"
#include "lpcvt/rvd.hpp"
#include "../worst.hpp"

using namespace lpcvt_test;
using quadapt::TriangleRule;
using quadapt::collapsed_gauss;
using quadapt::dunavant6;

namespace {

double polygon_area(const std::vector<Vec2>& v) {
  double a = 0;
  for (size_t k = 0; k < v.size(); ++k) {
    const Vec2 &p = v[k], &q = v[(k + 1) % v.size()];
    a += p.x() * q.y() - p.y() * q.x();
  }
  return 0.5 * a;
}

// integral of x^a y^b over the reference triangle (0,0),(1,0),(0,1): a! b! / (a+b+2)!
double mono_exact(int a, int b) {
  return std::tgamma(a + 1) * std::tgamma(b + 1) / std::tgamma(a + b + 3);
}

/// Sites: the equidistributed boundary points (fixed) followed by n random interior points.
std::vector<Vec2> sites_for(const Background& bg, int n, unsigned seed, int& nfixed) {
  auto curves = boundary_curves(bg);
  BoundaryPoints b = mesh_boundary(bg, curves);
  std::vector<Vec2> s = b.points;
  nfixed = static_cast<int>(s.size());
  auto in = random_inside(bg, n, seed);
  s.insert(s.end(), in.begin(), in.end());
  return s;
}

/// Max over the tested sites of |g_fd - g| / |g|, with the fourth-order central difference
/// (-E(x+2h) + 8E(x+h) - 8E(x-h) + E(x-2h)) / 12h (truncation O(h^4), rounding O(eps E / h)).
double fd_error(const Background& bg, std::vector<Vec2> x, const std::vector<int>& which, double p,
                double h) {
  EnergyResult r = lp_energy(bg, x, p, true);
  double worst = 0;
  auto energy_at = [&](int i, int d, double off) {
    Vec2 keep = x[i];
    x[i][d] = keep[d] + off;
    double e = lp_energy(bg, x, p, false).energy;
    x[i] = keep;
    return e;
  };
  for (int i : which) {
    Vec2 fd;
    for (int d = 0; d < 2; ++d)
      fd[d] = (-energy_at(i, d, 2 * h) + 8 * energy_at(i, d, h) - 8 * energy_at(i, d, -h) +
               energy_at(i, d, -2 * h)) / (12 * h);
    worst = quadapt_test::worst_of(worst, (fd - r.grad[i]).norm() / r.grad[i].norm());
  }
  return worst;
}

}  // namespace

TEST_CASE("triangle rules integrate monomials exactly up to their degree") {
  for (const TriangleRule* r : {&dunavant6()}) {
    for (int a = 0; a <= r->degree; ++a)
      for (int b = 0; a + b <= r->degree; ++b) {
        double s = 0;
        for (int q = 0; q < r->size(); ++q) s += r->w[q] * std::pow(r->bary[q][1], a) * std::pow(r->bary[q][2], b);
        CHECK(0.5 * s == doctest::Approx(mono_exact(a, b)).epsilon(1e-13));
      }
  }
  TriangleRule g = collapsed_gauss(11);
  for (int a = 0; a <= 11; ++a)
    for (int b = 0; a + b <= 11; ++b) {
      double s = 0;
      for (int q = 0; q < g.size(); ++q) s += g.w[q] * std::pow(g.bary[q][1], a) * std::pow(g.bary[q][2], b);
      CHECK(0.5 * s == doctest::Approx(mono_exact(a, b)).epsilon(1e-13));
    }
}

TEST_CASE("energy of one site on the unit square is exact") {
  Mesh m = quadapt::make_structured_quads(2, 2);
  set_frame(m, 1, 1, 0);  // M = I
  Background bg = Background::from_frame(m, 1.0, "mem");
  std::vector<Vec2> x = {{0.5, 0.5}};
  // p = 2: integral of |y - c|^2 = 2 * (1/12) = 1/6; p = 6: 2 * 2 (1/2)^7 / 7 = 1/224
  CHECK(lp_energy(bg, x, 2, false).energy == doctest::Approx(1.0 / 6).epsilon(1e-14));
  CHECK(lp_energy(bg, x, 6, false).energy == doctest::Approx(1.0 / 224).epsilon(1e-14));
  // a metric diag(2, 1) scales the first component: p = 6 -> (2^6 + 1) / 2 * 1/224
  set_frame(m, 0.5, 1, 0);
  Background bg2 = Background::from_frame(m, 1.0, "mem");
  CHECK(lp_energy(bg2, x, 6, false).energy == doctest::Approx(65.0 / 448).epsilon(1e-13));
}

TEST_CASE("clipped Voronoi pieces tile convex and non-convex domains") {
  for (int kind = 0; kind < 3; ++kind) {
    Mesh m = kind == 0 ? saddle_square(5) : kind == 1 ? l_shape() : square_with_hole();
    set_frame(m, 0.3, 0.3, 0);
    Background bg = Background::from_frame(m, 1.0, "mem");
    int nfixed = 0;
    auto x = sites_for(bg, 40, 7 + kind, nfixed);
    RestrictedVoronoi rvd(bg, x);
    auto pcs = rvd.all_pieces();
    double total = 0;
    std::vector<double> site_area(x.size(), 0.0);
    for (const auto& p : pcs) {
      double a = polygon_area(p.v);
      CHECK(a >= -1e-14);
      total += a;
      site_area[p.site] += a;
      // every piece point is nearest to its own site (up to rounding)
      Vec2 z = Vec2::Zero();
      for (auto& v : p.v) z += v / p.v.size();
      double di = (z - x[p.site]).norm();
      for (size_t j = 0; j < x.size(); ++j) CHECK(di <= (z - x[j]).norm() + 1e-12);
    }
    CHECK(total == doctest::Approx(bg.area()).epsilon(1e-12));
    for (size_t i = nfixed; i < x.size(); ++i) CHECK(site_area[i] > 0);
  }
}

TEST_CASE("gradient matches central finite differences on the smooth saddle metric (eq. 6.1)") {
  Mesh m = saddle_square(4);
  auto f = std::make_shared<SaddleMetric>();
  Background bg = Background::analytic(m, f, 1.0);
  int nfixed = 0;
  auto x = sites_for(bg, 30, 11, nfixed);
  // classify free sites: cells touching the boundary (a piece with a boundary edge) or not
  RestrictedVoronoi rvd(bg, x);
  std::vector<int> touches(x.size(), 0);
  for (const auto& p : rvd.all_pieces()) {
    const IntegrationCell& Q = bg.cell(p.cell);
    for (int l : p.label)
      if (l < 0) {
        int e = -1 - l;
        Vec2 mid = 0.5 * (Q.v[e] + Q.v[(e + 1) % Q.nv]);
        if (std::abs(std::abs(mid.x()) - 1.3) < 1e-12 || std::abs(std::abs(mid.y()) - 1.3) < 1e-12)
          touches[p.site] = 1;
      }
  }
  std::vector<int> inner, outer;
  for (int i = nfixed; i < static_cast<int>(x.size()); ++i) (touches[i] ? outer : inner).push_back(i);
  REQUIRE(inner.size() >= 5);
  REQUIRE(outer.size() >= 3);
  if (const char* e = std::getenv("LPCVT_FD_SCAN")) {
    for (double h : {1e-3, 3e-4, 1e-4, 3e-5, 1e-5})
      MESSAGE("h = " << h << ": " << fd_error(bg, x, inner, 6, h) << " " << fd_error(bg, x, outer, 6, h));
  }
  for (double p : {6.0, 2.0}) {
    double ei = fd_error(bg, x, inner, p, 1e-4);
    double eo = fd_error(bg, x, outer, p, 1e-4);
    MESSAGE("p = " << p << ": max relative FD error, interior sites " << ei << ", boundary cells " << eo);
    CHECK(ei < 1e-6);
    CHECK(eo < 1e-6);
  }
}

TEST_CASE("gradient matches finite differences with a discontinuous (16x16 sampled) metric") {
  Mesh m = saddle_square(16);
  SaddleMetric f;
  Background bg = Background::sampled(m, f, 1.0);
  int nfixed = 0;
  auto x = sites_for(bg, 30, 5, nfixed);
  std::vector<int> all;
  for (int i = nfixed; i < static_cast<int>(x.size()); ++i) all.push_back(i);
  double e = fd_error(bg, x, all, 6.0, 1e-4);
  MESSAGE("sampled metric: max relative FD error " << e);
  CHECK(e < 1e-6);
}

TEST_CASE("gradient matches finite differences on non-convex domains") {
  for (int kind = 0; kind < 2; ++kind) {
    Mesh m = kind == 0 ? l_shape() : square_with_hole();
    set_frame(m, 0.2, 0.4, 0.5);
    Background bg = Background::from_frame(m, 1.0, "mem");
    int nfixed = 0;
    auto x = sites_for(bg, 25, 3 + kind, nfixed);
    std::vector<int> all;
    for (int i = nfixed; i < static_cast<int>(x.size()); ++i) all.push_back(i);
    double e = fd_error(bg, x, all, 6.0, 1e-4);
    MESSAGE(std::string(kind == 0 ? "L-shape" : "hole") << ": max relative FD error " << e);
    CHECK(e < 1e-6);
  }
}

TEST_CASE("closed-form integration (even p, constant metric) equals the quadrature rule") {
  for (int kind = 0; kind < 2; ++kind) {
    Mesh m = kind == 0 ? saddle_square(4) : l_shape();
    set_frame(m, 0.2, 0.35, 0.4);
    Background bg = Background::from_frame(m, 1.0, "mem");
    int nfixed = 0;
    auto x = sites_for(bg, 40, 21 + kind, nfixed);
    for (double p : {2.0, 4.0, 6.0, 8.0}) {
      EnergyWorkspace quadrature;
      quadrature.settings.closed_form = false;
      EnergyResult a = lp_energy(bg, x, p, true, &quadrature);
      EnergyWorkspace ws;
      EnergyResult b = lp_energy(bg, x, p, true, &ws);
      EnergyResult c = lp_energy(bg, x, p, true, &ws);  // reused buffers: the same numbers
      double gmax = 0, gerr = 0;
      for (size_t i = 0; i < x.size(); ++i) {
        gmax = std::max(gmax, a.grad[i].norm());
        gerr = std::max(gerr, (a.grad[i] - b.grad[i]).norm());
        CHECK(b.grad[i] == c.grad[i]);
      }
      MESSAGE("p = " << p << ": energy " << a.energy << " vs " << b.energy << ", gradient difference "
                     << gerr / gmax << " (relative to the largest)");
      // both exact (Dunavant degree 6 up to p = 6, collapsed Gauss of degree p above)
      CHECK(b.energy == doctest::Approx(a.energy).epsilon(1e-12));
      CHECK(gerr < 1e-10 * gmax);
      CHECK(b.energy == c.energy);
    }
  }
}
