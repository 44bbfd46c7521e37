// Boundary points of the L_p-CVT on the true curves (lpcvt/geometry_boundary.hpp, docs/curved.md):
// on the circle to rounding, equidistributed in the metric, named by the geometry; the frame's
// resolution and domain are checked.
#include <doctest/doctest.h>

#include <cmath>
#include <memory>

#include "../mesh/curved_disk.hpp"
#include "core/error.hpp"
#include "lpcvt/geometry_boundary.hpp"

using namespace quadapt;
using namespace quadapt::lpcvt;

namespace {
Background disk_background(double h) {  // the inscribed polygon of the unit circle, M = I / h
  return Background::analytic(curvedtest::curved_disk(4, 1), std::make_shared<ConstantMetric>(Mat2::Identity() / h), 1.0);
}
const FunctionGeometry kCircle("circle.geo", {FunctionGeometry::circle("wall", Vec2(0, 0), 1.0)});
}  // namespace

TEST_CASE("geometry_boundary: a constant metric puts round(2 pi / h) equally spaced points on the circle") {
  for (double h : {0.3, 0.1, 0.05}) {
    CAPTURE(h);
    std::vector<BoundaryGroup> groups;
    const BoundaryPoints b = geometry_boundary(disk_background(h), kCircle, groups);
    REQUIRE(groups.size() == 1);
    CHECK(groups[0].name == "wall");
    const int n = static_cast<int>(std::lround(2 * M_PI / h));
    CHECK(static_cast<int>(b.points.size()) == n);
    CHECK(b.segments.size() == b.points.size());  // closed
    CHECK(b.curve_length[0] == doctest::Approx(2 * M_PI / h).epsilon(1e-5));
    double off = 0, lmin = 1e9, lmax = 0;
    for (const auto& p : b.points) off = std::max(off, std::abs(p.norm() - 1));
    for (const auto& s : b.segments) {
      const double l = (b.points[s[0]] - b.points[s[1]]).norm();
      lmin = std::min(lmin, l);
      lmax = std::max(lmax, l);
    }
    CHECK(off < 1e-15);
    CHECK(lmax / lmin - 1 < 1e-6);  // equal arcs (trapezoidal rule on 512+ samples of a constant)
  }
}

TEST_CASE("geometry_boundary: a frame too coarse for the curve gets a segment per 45 degrees of turn") {
  // M = I / 3 asks for 2 pi / 3 ~ 2 segments on the unit circle; the turn bound dL >= kappa / (pi / 4)
  // gives 8, each turning 45 degrees (the loop's frame is coarse where a small hole sits in a smooth
  // region: it was refused, "not resolved by the frame")
  for (double h : {3.0, 2.0}) {  // the sagitta term sqrt(2 / h) < 4 / pi: the turn bound alone
    CAPTURE(h);
    std::vector<BoundaryGroup> groups;
    const BoundaryPoints b = geometry_boundary(disk_background(h), kCircle, groups);
    CHECK(b.points.size() == 8);
    CHECK(b.curve_length[0] == doctest::Approx(8).epsilon(1e-6));
    for (const auto& s : b.segments)  // chord of a 45 degree arc
      CHECK((b.points[s[0]] - b.points[s[1]]).norm() == doctest::Approx(2 * std::sin(M_PI / 8)).epsilon(1e-6));
  }
  // where the metric asks for more (h = 0.3: 21 points), the turn bound is inactive (the test above)
}

TEST_CASE("geometry_boundary: a corner inside one curve, and a geometry outside the frame, are refused") {
  std::vector<BoundaryGroup> groups;
  // the square |x|, |y| <= 0.5 as ONE closed curve, t in [0, 4): a 90 degree turn no point count resolves
  auto side = [](double t) { return std::min(3, static_cast<int>(std::floor(t))); };
  const Vec2 corner[5] = {Vec2(-0.5, -0.5), Vec2(0.5, -0.5), Vec2(0.5, 0.5), Vec2(-0.5, 0.5), Vec2(-0.5, -0.5)};
  FunctionGeometry::Curve sq{"wall", 0, 4,
                             [&](double t) { const int k = side(t); return Vec2(corner[k] + (t - k) * (corner[k + 1] - corner[k])); },
                             [&](double t) { const int k = side(t); return Vec2(corner[k + 1] - corner[k]); },
                             [](double) { return Vec2(0, 0); }};
  const FunctionGeometry square("square.geo", {sq});
  CHECK_THROWS_WITH_AS(geometry_boundary(disk_background(0.1), square, groups),
                       doctest::Contains("square.geo: curve 'wall' (1) turns by 90 degrees within one of its"), InputError);
  const FunctionGeometry big("big.geo", {FunctionGeometry::circle("wall", Vec2(0, 0), 1.5)});
  CHECK_THROWS_WITH_AS(geometry_boundary(disk_background(0.1), big, groups),
                       doctest::Contains("outside the frame's domain"), InputError);
}

TEST_CASE("geometry_boundary: the metric length in the L_q norm (lpcvt --boundary-norm)") {
  // M = I / h on the unit circle: dL = |c'(t)|_q / h = (|sin t|^q + |cos t|^q)^(1/q) / h
  const double h = 0.1;
  for (double q : {2.0, 6.0}) {
    CAPTURE(q);
    const int n = 20000;  // composite Simpson over one period
    double L = 0;
    for (int k = 0; k <= n; ++k) {
      const double t = 2 * M_PI * k / n, w = (k == 0 || k == n) ? 1 : (k % 2 ? 4 : 2);
      L += w * std::pow(std::pow(std::abs(std::sin(t)), q) + std::pow(std::abs(std::cos(t)), q), 1 / q) / h;
    }
    L *= 2 * M_PI / (3.0 * n);
    std::vector<BoundaryGroup> groups;
    const BoundaryPoints b = geometry_boundary(disk_background(h), kCircle, groups, q);
    CHECK(b.curve_length[0] == doctest::Approx(L).epsilon(1e-5));
    CHECK(static_cast<int>(b.points.size()) == std::lround(L));
    if (q == 6) CHECK(L < 0.93 * 2 * M_PI / h);  // a rotation-dependent count: fewer points where the
                                                 // tangent is diagonal to the metric's axes
  }
}
