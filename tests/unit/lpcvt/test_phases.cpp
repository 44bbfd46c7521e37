// Lattice phases (lpcvt/phases.hpp, lattice.hpp): the offsets, the seed's registration with a
// phase, the lattice translated by it, and the auto rule.
#include <doctest/doctest.h>

#include <omp.h>

#include <cmath>
#include <set>

#include "core/error.hpp"
#include "helpers.hpp"
#include "lpcvt/lattice.hpp"
#include "lpcvt/metric_filter.hpp"
#include "lpcvt/phases.hpp"
#include "lpcvt/run.hpp"

using namespace lpcvt_test;

namespace {
constexpr double kPi = 3.14159265358979323846;
double frac(double x) { return x - std::floor(x); }
// distance of x from the nearest integer
double off_integer(double x) { return std::abs(x - std::round(x)); }
}  // namespace

TEST_CASE("phases: offset 0 is no offset; every axis alone takes K distinct values in [0, 1)") {
  CHECK(phase_offset(0, 1) == Vec2::Zero());
  for (int K = 2; K <= 16; ++K) {
    CHECK(phase_offset(0, K) == Vec2::Zero());
    std::set<long> xs, ys;
    for (int k = 0; k < K; ++k) {
      const Vec2 o = phase_offset(k, K);
      CHECK(o.x() >= 0);
      CHECK(o.x() < 1);
      CHECK(o.y() >= 0);
      CHECK(o.y() < 1);
      CHECK(off_integer(o.x() * K) < 1e-12);  // multiples of 1/K
      CHECK(off_integer(o.y() * K) < 1e-12);
      xs.insert(std::lround(o.x() * K));
      ys.insert(std::lround(o.y() * K));
    }
    CHECK(static_cast<int>(xs.size()) == K);
    CHECK(static_cast<int>(ys.size()) == K);
  }
  // spread over the square, not on its diagonal (K = 4: a = 3 -> the anti-diagonal pair)
  CHECK(phase_offset(1, 5) == Vec2(0.2, 0.6));
}

TEST_CASE("phases: the seed takes the walls' phase on a registered axis and the given phase on the other") {
  // lattice M = diag(1/h, 1/h); wall points at metric positions (k, k phi) from y0: all in phase
  // along axis 0 (integer k: frac = const), spread along axis 1 (k phi mod 1: irrational)
  const double h = 0.1, phi = 0.6180339887498949;
  const Mat2 M = Mat2::Identity() / h;
  const Vec2 y0(0.03, 0.07);
  std::vector<Vec2> fixed;
  for (int k = -5; k <= 5; ++k) fixed.push_back(y0 + h * Vec2(k + 0.2, k * phi));
  bool reg[2] = {false, false};
  const Vec2 y = register_seed(y0, M, fixed, 12.0, Vec2(0.25, 0.5), reg);
  CHECK(reg[0]);
  CHECK_FALSE(reg[1]);
  const Vec2 u = M * (y - y0);
  CHECK(std::abs(u.x() - 0.2) < 1e-9);  // registered: the walls' phase, not 0.25
  CHECK(std::abs(u.y() - 0.5) < 1e-12); // free: the requested phase
  // phase 0 leaves the free axis alone (the run without phases)
  const Vec2 y1 = register_seed(y0, M, fixed, 12.0, Vec2::Zero(), reg);
  CHECK(std::abs((M * (y1 - y0)).y()) < 1e-12);
}

TEST_CASE("phases: the lattice start is translated by M^-1 phase") {
  // constant frame at 30 degrees, stretch 4; no fixed points, so no axis is registered
  Mesh m = quadapt::make_structured_quads(8, 8, 0, 1, 0, 1);
  set_frame(m, 0.08, 0.02, 30 * kPi / 180);
  const Background bg = Background::from_frame(m, 1.0, "test");
  const Mat2 M = bg.metric(0, Vec2(0.0625, 0.0625));
  const std::vector<Vec2> p0 = lattice_points(bg, {});
  const std::vector<Vec2> p1 = lattice_points(bg, {}, 0.75, 10000000, Vec2(0.5, 0.25));
  REQUIRE(p0.size() > 100);
  REQUIRE(p1.size() > 100);
  CHECK(std::abs(static_cast<double>(p1.size()) - p0.size()) < 0.1 * p0.size());
  // every point of p1 sits at lattice coordinates (i + 0.5, j + 0.25) relative to p0's seed
  int bad = 0;
  for (const Vec2& p : p1) {
    const Vec2 u = M * (p - p0[0]);
    if (off_integer(u.x() - 0.5) > 1e-6 || off_integer(u.y() - 0.25) > 1e-6) ++bad;
  }
  CHECK(bad == 0);
  // and p0 is the unshifted lattice
  for (const Vec2& p : p0) {
    const Vec2 u = M * (p - p0[0]);
    CHECK(off_integer(u.x()) < 1e-6);
    CHECK(off_integer(u.y()) < 1e-6);
  }
  (void)frac;
}

TEST_CASE("phases: auto runs kAutoPhases phases on a constant frame up to kAutoPhasePoints points, one above") {
  Mesh m = quadapt::make_structured_quads(4, 4, 0, 1, 0, 1);
  set_frame(m, 0.05, 0.05, 0);  // metric area 1 / 0.05^2 = 400
  const Background small = Background::from_frame(m, 1.0, "test");
  CHECK(small.metric_area() == doctest::Approx(400));
  CHECK(metric_spread(small) < 1e-12);
  CHECK(auto_phases(small) == kAutoPhases);
  CHECK(auto_phases(small.scaled(std::sqrt(kAutoPhasePoints / 400) * 1.01)) == 1);
  CHECK(auto_phases(small.scaled(std::sqrt(kAutoPhasePoints / 400) * 0.99)) == kAutoPhases);
}

TEST_CASE("phases: auto runs one phase on a graded frame (metric_spread above kAutoPhaseSpread)") {
  // a turned, reflected constant frame is constant: its 𝓜 = MᵀM does not see the reflection
  Mesh m = quadapt::make_structured_quads(4, 4, 0, 1, 0, 1);
  set_frame(m, 0.06, 0.015, 0.7);
  auto& f = m.cell_fields[0];
  for (int c = 0; c < m.num_cells(); c += 2)
    for (int k : {0, 1}) f(c, k) = -f(c, k);  // every other cell reflected (det M < 0)
  CHECK(metric_spread(Background::from_frame(m, 1.0, "test")) < 1e-12);
  CHECK(auto_phases(Background::from_frame(m, 1.0, "test")) == kAutoPhases);
  // sizes h in the left half, s h in the right half: log 𝓜 = -2 ln h I and -2 ln(s h) I, the mean
  // halfway, so the spread is ln s |I|_F = sqrt(2) ln s
  for (double s : {1.05, 1.2, 2.0}) {
    set_frame(m, 0.05, 0.05, 0);
    for (int c = 0; c < m.num_cells(); ++c)
      if (quadapt::cell_centroid(m, c).x() > 0.5)
        for (int k : {0, 4}) f(c, k) /= s;
    const Background bg = Background::from_frame(m, 1.0, "test");
    CHECK(metric_spread(bg) == doctest::Approx(std::sqrt(2.0) * std::log(s)).epsilon(1e-12));
    CHECK(auto_phases(bg) == (std::sqrt(2.0) * std::log(s) <= kAutoPhaseSpread ? kAutoPhases : 1));
  }
  // a 4:1 frame turned by 10 degrees in the right half: graded, one phase
  set_frame(m, 0.06, 0.015, 0);
  Mesh turned = m;
  set_frame(turned, 0.06, 0.015, 10 * kPi / 180);
  for (int c = 0; c < m.num_cells(); ++c)
    if (quadapt::cell_centroid(m, c).x() > 0.5)
      for (int k = 0; k < 9; ++k) f(c, k) = turned.cell_fields[0](c, k);
  const Background bg = Background::from_frame(m, 1.0, "test");
  CHECK(metric_spread(bg) > kAutoPhaseSpread);
  CHECK(auto_phases(bg) == 1);
}

TEST_CASE("phases: run two at a time on two threads, the caller's thread count is kept, the same run as on one") {
  // run_phases sets one thread inside its parallel region (each phase's own regions): that
  // setting belongs to the region's tasks and must not leak to the caller; the kept run must not
  // depend on the thread count
  Mesh m = quadapt::make_structured_quads(8, 8, 0, 1, 0, 1);
  set_frame(m, 0.06, 0.015, 45 * kPi / 180);  // walls oblique to the lattice: the phases differ
  const Background bg = Background::from_frame(m, 1.0, "test");
  LpcvtOptions o = LpcvtOptions::for_frame();
  const int caller = omp_get_max_threads();
  omp_set_num_threads(2);
  const PhaseRuns two = run_phases(bg, o, 3);
  CHECK(omp_get_max_threads() == 2);
  omp_set_num_threads(1);
  const PhaseRuns one = run_phases(bg, o, 3);
  CHECK(omp_get_max_threads() == 1);
  omp_set_num_threads(caller);
  CHECK(two.kept == one.kept);
  REQUIRE(two.best.sites.size() == one.best.sites.size());
  CHECK(two.best.sites == one.best.sites);
  REQUIRE(two.runs.size() == one.runs.size());
  for (size_t k = 0; k < two.runs.size(); ++k)
    CHECK(two.runs[k].value("irregular", -1) == one.runs[k].value("irregular", -1));
  MESSAGE("kept phase " << one.kept << " of 3; irregular counts " << one.runs.dump());
}

TEST_CASE("check_job: an option outside the tool's range is an InputError naming the field, before any work") {
  // a library caller's p = 0 or negative scale ran and returned a poor mesh (a review, session 38)
  CHECK_NOTHROW(check_job(LpcvtJob::for_frame()));
  CHECK_NOTHROW(check_job(LpcvtJob::for_analytic()));
  const auto refused = [](auto set, const char* field) {
    LpcvtJob j = LpcvtJob::for_frame();
    set(j);
    CHECK_THROWS_WITH_AS(check_job(j), doctest::Contains(field), quadapt::InputError);
    nlohmann::json rep;
    CHECK_THROWS_AS(saddle_background(4, true, j, rep, {}), quadapt::InputError);
  };
  refused([](LpcvtJob& j) { j.lpcvt.p = 0; }, "LpcvtOptions::p = 0: the L_p exponent must be in [2, 32]");
  refused([](LpcvtJob& j) { j.lpcvt.p = std::nan(""); }, "LpcvtOptions::p = nan");
  refused([](LpcvtJob& j) { j.scale = -1; }, "LpcvtJob::scale = -1");
  refused([](LpcvtJob& j) { j.cells_per_triangle = -2; }, "LpcvtJob::cells_per_triangle = -2");
  refused([](LpcvtJob& j) { j.gradation = 0.5; }, "LpcvtJob::gradation = 0.5");
  refused([](LpcvtJob& j) { j.lpcvt.lbfgs.max_iterations = 0; }, "LbfgsOptions::max_iterations = 0");
  refused([](LpcvtJob& j) { j.lpcvt.lattice_phase = Vec2(1, 0); }, "LpcvtOptions::lattice_phase.x = 1");
}
