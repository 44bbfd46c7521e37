#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "estimate/directional.hpp"
#include "estimate/estimate_frame.hpp"
#include "estimate/polynomial_model.hpp"
#include "estimate/interpolate.hpp"
#include "mesh/jitter.hpp"
#include "test_util.hpp"
#include "../worst.hpp"

using namespace quadapt;
using quadapt::testutil::angle_diff_mod_pi;

namespace {
Mesh with_u(Mesh m, int p, const std::function<double(double, double)>& f) {
  m.set_field(interpolate_dg(m, p, f));
  return m;
}
}  // namespace

TEST_CASE("estimate on a degree-p field holding x^p y + c x y^p: A1, A2, phi match brute force") {
  for (int p = 2; p <= 3; ++p) {
    CAPTURE(p);
    const double c = 0.4;
    // axis-aligned rectangles of varying size: Q_p holds x^p y exactly (bilinear or sheared
    // cells would not)
    Mesh aff = make_structured_quads(6, 6);
    for (auto& x : aff.nodes) x = Vec2(x.x() + 0.3 * x.x() * x.x(), 0.8 * x.y() - 0.2 * x.y() * x.y());
    Mesh m = with_u(aff, p,
                    [&](double x, double y) {
                      return std::pow(x, p) * y + c * x * std::pow(y, p) + (p == 3 ? 0.3 * x * x * y * y : 0.0) + x - 2 * y;
                    });
    EstimateOptions thesis;
    thesis.model = ErrorModel::Thesis;
    EstimateResult r = estimate_frame(m, thesis);
    const EstimateResult poly = estimate_frame(m);  // the default, polynomial model
    CHECK(r.p == p);
    // brute force on the exact top-degree part: P(φ) = cos^p sin + c cos sin^p (+ 0.3 cos^2 sin^2)
    auto P = [&](double ph) {
      const double cs = std::cos(ph), sn = std::sin(ph);
      return std::pow(cs, p) * sn + c * cs * std::pow(sn, p) + (p == 3 ? 0.3 * cs * cs * sn * sn : 0.0);
    };
    double best = 0, bphi = 0;
    for (int k = 0; k < 2000000; ++k) {
      double ph = M_PI * k / 2000000.0;
      double v = std::abs(P(ph));
      if (v > best) { best = v; bphi = ph; }
    }
    const double a2 = std::abs(P(bphi + M_PI / 2));
    for (int k = 0; k < m.num_cells(); ++k) {
      CHECK(r.A1[k] == doctest::Approx(best).epsilon(1e-9));
      CHECK(r.A2[k] == doctest::Approx(a2).epsilon(1e-5));
      CHECK(angle_diff_mod_pi(r.phi[k], bphi) < 1e-5);
      CHECK(angle_diff_mod_pi(r.theta[k], bphi - M_PI / 2) < 1e-5);
      CHECK(r.rho[k] == doctest::Approx(std::pow(best / a2, 1.0 / (p + 1))).epsilon(1e-4));
    }
    // the polynomial model keeps the orientation and takes ρ from the whole term
    std::vector<double> a(p + 2, 0.0);
    a[p] += 1;
    a[1] += c;
    if (p == 3) a[2] += 0.3;
    const PolynomialShape ps = polynomial_stretch(a, 2, 1e6, bphi - M_PI / 2);
    CHECK(std::abs(ps.rho - std::pow(best / a2, 1.0 / (p + 1))) > 0.05 * ps.rho);  // the models differ here
    for (int k = 0; k < m.num_cells(); ++k) {
      CHECK(angle_diff_mod_pi(poly.phi[k], bphi) < 1e-5);
      CHECK(angle_diff_mod_pi(poly.theta[k], bphi - M_PI / 2) < 1e-5);
      CHECK(poly.rho[k] == doctest::Approx(ps.rho).epsilon(1e-4));
    }
  }
}

TEST_CASE("u = tanh(50 x): frames thin in x (refinement along the largest derivative)") {
  // [-0.5,0.5]^2, 32x32 (h = 1.6 front widths), structured and perturbed (30% of h), p = 1..3,
  // both patch kinds. Every cell with a strong feature (A1 >= 20% of the largest) gets a frame
  // whose LONG axis is along y (theta = phi + pi/2) and whose x-extent is the smaller one; the
  // median direction error is below 5 degrees. On the structured mesh the vertex (3x3) patch
  // is a tensor domain, so the reconstruction of a function of x alone is exactly y-free.
  for (int p = 1; p <= 3; ++p)
    for (int perturbed = 0; perturbed <= 1; ++perturbed)
      for (PatchKind kind : {PatchKind::Face, PatchKind::Vertex}) {
        CAPTURE(p);
        CAPTURE(perturbed);
        CAPTURE(static_cast<int>(kind));
        Mesh base = perturbed ? make_perturbed_quads(32, 32, 0.3, 17) : make_structured_quads(32, 32);
        Mesh m = with_u(testutil::rescale(base, -0.5, 0.5, -0.5, 0.5), p, [](double x, double) { return std::tanh(50 * x); });
        EstimateOptions o;
        o.patch = kind;
        EstimateResult r = estimate_frame(m, o);
        double amax = 0;
        for (double a : r.A1) amax = std::max(amax, a);
        std::vector<double> errs;
        double minrho = 1e300;
        for (int c = 0; c < m.num_cells(); ++c) {
          if (r.A1[c] < 0.2 * amax) continue;
          errs.push_back(angle_diff_mod_pi(r.phi[c], 0));
          minrho = std::min(minrho, r.rho[c]);
          CHECK(angle_diff_mod_pi(r.theta[c], r.phi[c] + M_PI / 2) < 1e-12);
          const double h1 = std::sqrt(r.rho[c]), h2 = 1 / std::sqrt(r.rho[c]);
          const double ex = std::abs(h1 * std::cos(r.theta[c])) + std::abs(h2 * std::sin(r.theta[c]));
          const double ey = std::abs(h1 * std::sin(r.theta[c])) + std::abs(h2 * std::cos(r.theta[c]));
          CHECK(ex < ey);
        }
        REQUIRE(errs.size() >= 64);
        std::sort(errs.begin(), errs.end());
        const double median = errs[errs.size() / 2], worst = errs.back();
        CHECK(median < 5 * M_PI / 180);
        CHECK(minrho > 1.05);
        if (!perturbed && kind == PatchKind::Vertex) CHECK(worst < 1e-9);
        MESSAGE("tanh(50x) p=" << p << " perturbed=" << perturbed << " patch=" << std::string(kind == PatchKind::Face ? "face" : "vertex")
                               << ": median " << median * 180 / M_PI << " deg, worst " << worst * 180 / M_PI
                               << " deg, min rho " << minrho << " over " << errs.size() << " cells");
      }
}

TEST_CASE("rotated front tanh(40(x cos a + y sin a - 0.6)): frames aligned within a few degrees") {
  // Perturbed 48x48 mesh (h ~ front width / 1.2), p = 2. The cells with a strong feature
  // (A1 >= 50% of the largest) are aligned within 7 degrees with the thesis's face patch and
  // within 4 degrees with the 3x3 vertex patch (measured: 6.3 and 3.5); the median front cell
  // (A1 >= 10%) within 2 degrees (measured ~0.6-1.1). (Where the 3rd derivative changes sign along the normal, A1 is small and
  // its direction is set by the other terms: those cells are not expected to align.)
  const int p = 2;
  for (PatchKind kind : {PatchKind::Face, PatchKind::Vertex})
  for (double a : {0.2, 0.5, 0.785398, 1.1, 1.4}) {
    CAPTURE(a);
    CAPTURE(static_cast<int>(kind));
    Mesh m = with_u(make_perturbed_quads(48, 48, 0.2, 4), p, [a](double x, double y) {
      return std::tanh(40 * (x * std::cos(a) + y * std::sin(a) - 0.6));
    });
    EstimateOptions o;
    o.patch = kind;
    EstimateResult r = estimate_frame(m, o);
    double amax = 0;
    for (double v : r.A1) amax = std::max(amax, v);
    double worst = 0;
    std::vector<double> errs;
    for (int c = 0; c < m.num_cells(); ++c) {
      const double e = angle_diff_mod_pi(r.phi[c], a);
      if (r.A1[c] >= 0.5 * amax) worst = quadapt_test::worst_of(worst, e);
      if (r.A1[c] >= 0.1 * amax) errs.push_back(e);
      if (r.A1[c] > 0) CHECK(angle_diff_mod_pi(r.theta[c], r.phi[c] + M_PI / 2) < 1e-12);
    }
    std::sort(errs.begin(), errs.end());
    REQUIRE(errs.size() > 50);
    const double median = errs[errs.size() / 2];
    CHECK(worst < (kind == PatchKind::Face ? 7 : 4) * M_PI / 180);
    CHECK(median < 2 * M_PI / 180);
    MESSAGE("patch " << std::string(kind == PatchKind::Face ? "face" : "vertex") << " a = " << a << ": strong cells worst " << worst * 180 / M_PI << " deg, median " << median * 180 / M_PI
                   << " deg over " << errs.size() << " front cells");
  }
}

TEST_CASE("vanishing derivatives: no NaN or infinity") {
  // p = 2 field of a quadratic: the cubic part vanishes (A1 ~ rounding) -> isotropic, finite
  Mesh m = with_u(make_perturbed_quads(6, 6, 0.2, 1), 2, [](double x, double y) { return 1 + x * x - x * y; });
  EstimateResult r = estimate_frame(m);
  for (int c = 0; c < m.num_cells(); ++c) {
    CHECK(std::isfinite(r.theta[c]));
    CHECK(std::isfinite(r.rho[c]));
    CHECK(std::isfinite(r.B[c]));
    CHECK(r.A1[c] < 1e-8);
    CHECK(r.B[c] < 1e-12);
  }
  // constant field: exactly isotropic, B = 0
  Mesh k = with_u(make_structured_quads(4, 4), 1, [](double, double) { return 3.0; });
  EstimateResult rk = estimate_frame(k);
  for (int c = 0; c < k.num_cells(); ++c) {
    CHECK(rk.rho[c] == 1);
    CHECK(rk.theta[c] == 0);
    CHECK(rk.B[c] == doctest::Approx(0).epsilon(1e-20));
  }
  // x^3 with p = 2: A2 = 0 exactly along y; rho capped, B finite and positive
  Mesh c3 = with_u(make_structured_quads(4, 4), 2, [](double x, double) { return x * x * x; });
  EstimateOptions o;
  o.max_anisotropy = 100;
  EstimateResult r3 = estimate_frame(c3, o);
  for (int c = 0; c < c3.num_cells(); ++c) {
    CHECK(r3.rho[c] <= 100 + 1e-9);
    CHECK(std::isfinite(r3.B[c]));
    CHECK(r3.B[c] > 0);
  }
}

TEST_CASE("noise-floor cells: every directional field zero, phi too") {
  // u = 1e-13 (x + y)^3 (noise: below the floor) for x < 1/2 and (x - 1/2)^3 beyond, p = 2: the
  // left cells carry no derivative. Their phi was the noise's direction (45 degrees here), which
  // differs between a field and its mirror image
  for (bool mirror : {false, true}) {
    CAPTURE(mirror);
    Mesh m = with_u(make_structured_quads(8, 8), 2, [&](double x, double y) {
      const double s = mirror ? 0.5 - x : x - 0.5;
      return s > 0 ? s * s * s : 1e-13 * std::pow(x + y, 3);
    });
    const EstimateResult r = estimate_frame(m);
    int free = 0;
    for (int c = 0; c < m.num_cells(); ++c) {
      if (r.B[c] != 0) continue;
      ++free;
      CHECK(r.A1[c] == 0);
      CHECK(r.A2[c] == 0);
      CHECK(r.phi[c] == 0);
      CHECK(r.theta[c] == 0);
      CHECK(r.rho[c] == 1);
    }
    CHECK(free >= 16);  // at least the two columns away from x = 1/2
  }
}

TEST_CASE("estimate input errors") {
  Mesh m = make_structured_quads(3, 3);
  CHECK_THROWS_AS(estimate_frame(m, {}, "sol.msh"), InputError);
  try {
    estimate_frame(m, {}, "sol.msh");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("sol.msh") == 0);
  }
  // vertex-valued (non-DG) field of the right name
  CellNodeField v;
  v.name = "u";
  v.per_cell = 4;
  v.degree = -1;
  v.values.assign(36, 0.0);
  m.set_field(v);
  CHECK_THROWS_AS(estimate_frame(m), InputError);
}

TEST_CASE("shape mesh carries theta, rho, B, A1, A2, phi, p and no solution") {
  Mesh m = with_u(make_structured_quads(4, 4), 2, [](double x, double y) { return std::sin(3 * x) * y; });
  EstimateResult r = estimate_frame(m);
  Mesh s = make_shape_mesh(m, r);
  for (const char* n : {"theta", "rho", "B", "A1", "A2", "phi", "p"}) {
    CAPTURE(n);
    REQUIRE(s.cell_field(n) != nullptr);
    CHECK(s.cell_field(n)->values.size() == 16);
  }
  CHECK(s.cell_node_field("u") == nullptr);
  CHECK((*s.cell_field("p"))(3) == 2);
}

TEST_CASE("the error model does not depend on the unit of length") {
  // The same problem on [0, s]^2 (perturbed 16 x 16 quads, u = atan(60 (r - 0.9)) about
  // (-0.25 s, -0.25 s) in the scaled coordinates): A1 s^(p+1), A2 s^(p+1), rho and theta equal
  // to rounding for s a power of two (the H1 product's L, a power of two, scales with them), and
  // within 1 % for metres to millimetres and other factors (L then off by at most sqrt 2). With
  // the physical product alone (L = 1 on every domain) A1 s^3 was 357.3 at s = 1 and 528.6 at
  // s = 100 on a rectangle (docs/estimate-frame.md).
  const int p = 2;
  const Mesh base = make_perturbed_quads(16, 16, 0.25, 5);
  auto solve = [&](double s, ErrorModel model) {
    Mesh m = testutil::rescale(base, 0, s, 0, s);
    m = with_u(std::move(m), p, [s](double x, double y) {
      return std::atan(60 * (std::hypot(x / s + 0.25, y / s + 0.25) - 0.9));
    });
    EstimateOptions o;
    o.model = model;
    return estimate_frame(m, o);
  };
  for (ErrorModel model : {ErrorModel::Thesis, ErrorModel::Polynomial}) {
  CAPTURE(static_cast<int>(model));
  const bool thesis = model == ErrorModel::Thesis;
  const EstimateResult ref = solve(1.0, model);
  const double a1_max = *std::max_element(ref.A1.begin(), ref.A1.end());
  for (const double s : {1.0 / 1024, 0.5, 8.0, 1024.0, 1e-3, 10.0, 1e3}) {
    CAPTURE(s);
    const bool power_of_two = std::exp2(std::round(std::log2(s))) == s;
    const EstimateResult r = solve(s, model);
    const double f = std::pow(s, p + 1);
    const double fB = std::pow(s, 2.0 * (p + 1));  // B = c (A1 A2)^(q/2), q = 2
    double worst_a = 0, worst_rho = 0, worst_theta = 0;
    std::vector<double> drho;
    for (size_t c = 0; c < ref.A1.size(); ++c) {
      if (ref.A1[c] < 1e-3 * a1_max) continue;  // the flat cells: no shape to compare
      // the thesis's A1; the polynomial model's B (its A1 is an equivalent that moves with ρ)
      worst_a = quadapt_test::worst_of(worst_a, thesis ? std::abs(r.A1[c] * f - ref.A1[c]) / ref.A1[c]
                                                       : std::abs(r.B[c] * fB - ref.B[c]) / ref.B[c]);
      const double d = std::abs(r.rho[c] - ref.rho[c]) / ref.rho[c];
      worst_rho = quadapt_test::worst_of(worst_rho, d);
      drho.push_back(d);
      if (ref.rho[c] > 1.05) worst_theta = quadapt_test::worst_of(worst_theta, angle_diff_mod_pi(r.theta[c], ref.theta[c]));
    }
    std::sort(drho.begin(), drho.end());
    const double median_rho = drho[drho.size() / 2];
    MESSAGE("s = " << s << std::string(thesis ? ": worst relative A1 " : ": worst relative B ") << worst_a << ", rho " << worst_rho << " (median " << median_rho
                   << "), theta " << worst_theta << " rad");
    if (power_of_two) {
      CHECK(worst_a < 1e-7);
      CHECK(worst_rho < 1e-7);
      CHECK(worst_theta < 1e-7);
    } else {
      // L is then off by up to sqrt 2 from s: the top derivative moves little, the stretch of the
      // nearly one-dimensional cells (A2 near zero) more, and B (∝ A1 A2) with it (measured: A1
      // 1.2e-3, B 5.1e-3 at s = 10)
      CHECK(worst_a < (thesis ? 1e-3 : 1e-2));
      CHECK(worst_theta < 1e-3);
      CHECK(median_rho < 1e-2);
    }
  }
  }
}

TEST_CASE("a harmonic solution gets nearly square frames from the default model, not from the thesis's") {
  // u = e^x cos y + x y is harmonic: its (p+1)-th directional Taylor term is ∝ cos((p+1)φ − ψ),
  // which for odd p+1 vanishes across its maximum, so the thesis's A2 ~ 0 and ρ is large. The
  // polynomial model integrates the whole term and keeps the elements nearly square (on the
  // 3:1 rectangle's loop, docs/estimate-frame.md: 9.58e-7 -> 4.66e-7 at ~31,000 DOFs).
  const int p = 2;
  Mesh m = with_u(testutil::rescale(make_perturbed_quads(24, 8, 0.2, 3), 0, 3, 0, 1), p,
                  [](double x, double y) { return std::exp(x) * std::cos(y) + x * y; });
  auto median_rho = [&](ErrorModel model) {
    EstimateOptions o;
    o.model = model;
    EstimateResult r = estimate_frame(m, o);
    std::vector<double> rho = r.rho;
    std::sort(rho.begin(), rho.end());
    return rho[rho.size() / 2];
  };
  const double poly = median_rho(ErrorModel::Polynomial), thesis = median_rho(ErrorModel::Thesis);
  MESSAGE("median rho: polynomial " << poly << ", thesis " << thesis);
  // measured 1.01 and 4.14: the thesis's A2 is the reconstruction's error across the maximum
  // (A2 / A1 ~ 0.014), not the solution's
  CHECK(poly < 1.3);
  CHECK(thesis > 3);
}

TEST_CASE("the observed-error floor raises B at a singular point and leaves a smooth field nearly alone") {
  // u = r^0.6 about the centre node of [-1,1]^2 (16 x 16, p = 2): the cells at the centre hold a
  // singularity no degree-3 Taylor term describes, so the reconstruction's misfit there is far
  // above its usual ratio to the model's error and their B is raised; elsewhere u is smooth.
  const int p = 2;
  const Mesh base = testutil::rescale(make_structured_quads(16, 16), -1, 1, -1, 1);
  auto run = [&](const std::function<double(double, double)>& u, double floor) {
    EstimateOptions o;
    o.observed_floor = floor;
    return estimate_frame(with_u(base, p, u), o);
  };
  auto singular = [](double x, double y) { return std::pow(x * x + y * y + 1e-300, 0.3); };
  const EstimateResult off = run(singular, 0), on = run(singular, 4);
  CHECK(off.cells_raised == 0);
  CHECK(on.misfit_ratio_median > 0);
  int centre_raised = 0;
  for (int c = 0; c < base.num_cells(); ++c) {
    CHECK(on.B[c] >= off.B[c]);
    CHECK(on.B[c] <= 64 * off.B[c] * (1 + 1e-12));  // the raise is capped
    CHECK(on.rho[c] == off.rho[c]);  // the floor scales B, never the shape
    const Vec2 x = cell_centroid(base, c);
    if (x.norm() < 0.1 && on.B[c] > 10 * off.B[c]) ++centre_raised;
  }
  CHECK(centre_raised == 4);  // the four cells at the singular node
  MESSAGE("singular: " << on.cells_raised << " of " << base.num_cells() << " cells raised, median ratio "
                       << on.misfit_ratio_median);
  // a smooth field: few cells raised, and by little
  const EstimateResult smooth = run([](double x, double y) { return std::sin(2 * x) * std::exp(y); }, 4);
  const EstimateResult smooth_off = run([](double x, double y) { return std::sin(2 * x) * std::exp(y); }, 0);
  double worst = 1;
  for (int c = 0; c < base.num_cells(); ++c)
    if (smooth_off.B[c] > 0) worst = std::max(worst, smooth.B[c] / smooth_off.B[c]);
  MESSAGE("smooth: " << smooth.cells_raised << " cells raised, largest factor " << worst);
  // measured: 8 of 256 cells, by at most 1.65x; at the singularity 20 cells, the four at the node > 10x
  CHECK(smooth.cells_raised < base.num_cells() / 10);
  CHECK(worst < 2.5);
  // the floor's range
  EstimateOptions bad;
  bad.observed_floor = 0.5;
  CHECK_THROWS_AS(estimate_frame(with_u(base, p, singular), bad), InputError);
}

TEST_CASE("the observed-error floor leaves a field the model describes exactly alone (rounding is not misfit)") {
  // u_h holds a polynomial of P^{p+1} ∩ Q_p on axis-aligned rectangles: the reconstruction is
  // exact, its misfit is rounding (~1e-16), and B must be the closed form's on every cell — the
  // floor ignores cells whose misfit is at rounding level. Before, the cells whose rounding was
  // above 4x the median rounding were raised: 15-19 of 64 cells, by up to the cap of 64 (a review).
  for (int p = 1; p <= 3; ++p) {
    CAPTURE(p);
    Mesh aff = make_structured_quads(8, 8);
    for (auto& x : aff.nodes) x = Vec2(x.x() + 0.3 * x.x() * x.x(), 0.8 * x.y() - 0.2 * x.y() * x.y());
    auto u = [p](double x, double y) {
      if (p == 1) return x * y + 0.3 * x - y;
      if (p == 2) return -2 * x * x * y + x * y * y + x * x - y;
      return x * x * x * y + 0.5 * x * x * y * y - 0.2 * x * y * y * y + x * x * x;
    };
    const Mesh m = with_u(aff, p, u);
    EstimateOptions on, off;
    off.observed_floor = 0;
    const EstimateResult a = estimate_frame(m, on), b = estimate_frame(m, off);
    CHECK(a.cells_raised == 0);
    for (int c = 0; c < m.num_cells(); ++c) CHECK(a.B[c] == b.B[c]);
  }
}

TEST_CASE("u and u + const give the same shape: the noise floor scales with u's oscillation, not max|u|") {
  // A Gaussian on 32 x 32, p = 2, with and without an offset of 1e3 (a temperature in kelvin).
  // The cells without a derivative and B agree (the observed-error floor off: it is tested above);
  // with the floor at 1e-10 max|u| the offset zeroed 252 more cells and moved B everywhere near
  // them (a review).
  const int p = 2;
  const Mesh base = make_structured_quads(32, 32);
  auto run = [&](double offset) {
    EstimateOptions o;
    o.observed_floor = 0;
    return estimate_frame(
        with_u(base, p, [offset](double x, double y) {
          return offset + std::exp(-((x - 0.5) * (x - 0.5) + (y - 0.5) * (y - 0.5)) / 0.01);
        }),
        o);
  };
  const EstimateResult a = run(0), b = run(1e3);
  const double h3 = std::pow(1.0 / 32, 3);
  int zero_a = 0, zero_b = 0;
  double lost = 0, worst = 0;  // the largest A1 h^3 of a cell zeroed by the offset; B's largest change
  for (int c = 0; c < base.num_cells(); ++c) {
    zero_a += a.B[c] == 0;
    zero_b += b.B[c] == 0;
    if (a.B[c] > 0 && b.B[c] == 0) lost = std::max(lost, a.A1[c] * h3);
    if (a.A1[c] * h3 > 1e-6) worst = std::max(worst, std::abs(b.B[c] / a.B[c] - 1));
  }
  MESSAGE("cells without a derivative: " << zero_a << " without offset, " << zero_b << " with 1e3; the largest A1 h^3 lost "
                                         << lost << ", B's largest relative change " << worst);
  // only cells whose degree-3 term changes u by about the offset's rounding (1e3 ε 1e3 = 2.2e-10)
  // are lost; with the floor at 1e-10 max|u| every cell below 1e-7 was
  CHECK(lost < 1e-8);
  // where u's third derivatives change u by 1e-6 or more, B is kept to the offset's rounding (measured 2e-5)
  CHECK(worst < 1e-3);
}

TEST_CASE("stretched cells: an offset's rounding is not taken for a derivative") {
  // u = 1000 + x (no degree-3 term at all) on a jittered 12 x 12 grid squeezed 1000x in y, p = 2:
  // the fit's rounding across a cell of aspect ~1000 is ε U (aspect)^(3/2) on the scale A1 h_k^3,
  // far above ε U; every cell must come out without a derivative (before the stretch factor 110 of
  // 144 cells got noise directions with ρ up to 3000: a review). u = x alike.
  Mesh m = make_structured_quads(12, 12);
  JitterOptions j;
  j.fraction = 0.3;
  j.seed = 2;
  jitter_interior_nodes(m, j);
  for (auto& x : m.nodes) x.y() *= 1e-3;
  for (double offset : {0.0, 1000.0}) {
    CAPTURE(offset);
    const EstimateResult r = estimate_frame(with_u(m, 2, [offset](double x, double) { return offset + x; }));
    int without = 0;
    for (int c = 0; c < m.num_cells(); ++c) without += r.B[c] == 0;
    CHECK(without == m.num_cells());
  }
}
