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

TEST_CASE("geometry_boundary: a frame too coarse for the curve, and a geometry outside the frame, are refused") {
  std::vector<BoundaryGroup> groups;
  CHECK_THROWS_WITH_AS(geometry_boundary(disk_background(3.0), kCircle, groups),
                       doctest::Contains("circle.geo: curve 'wall' (1) is not resolved by the frame"), InputError);
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
