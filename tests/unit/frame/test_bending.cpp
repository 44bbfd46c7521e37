// lib/frame/bending: B = κ h1^2 / h2 against circles of known curvature; zero on straight rows;
// independent of the axes.
#include <doctest/doctest.h>

#include <cmath>

#include "frame/bending.hpp"
#include "frame/frame.hpp"
#include "../worst.hpp"

using namespace quadapt;

namespace {
// n x n cells on [x0, x0 + 1]^2 turned by `turn` about the origin; per cell the long axis (h1)
// along the circle about the origin through its centroid, or at `theta` when circles is false
struct Case {
  Mesh m;
  std::vector<Mat2> M;
};
Case make(int n, double x0, double turn, bool circles, double theta = 0, double h1 = 0.05, double h2 = 0.005) {
  Case k{make_structured_quads(n, n, x0, x0 + 1, x0, x0 + 1), {}};
  const double c = std::cos(turn), s = std::sin(turn);
  for (auto& x : k.m.nodes) x = Vec2(c * x.x() - s * x.y(), s * x.x() + c * x.y());
  for (int q = 0; q < k.m.num_cells(); ++q) {
    const Vec2 x = cell_centroid(k.m, q);
    const double t = circles ? std::atan2(x.y(), x.x()) + M_PI / 2 : theta + turn;
    k.M.push_back(frame_inverse(std::sqrt(h1 * h2), h1 / h2, t));
  }
  return k;
}
}  // namespace

TEST_CASE("straight rows do not bend, at any angle; isotropic cells have no B") {
  for (double theta : {0.0, 0.4, 1.1}) {
    const Case k = make(12, 0, 0, false, theta);
    for (double b : frame_bending(k.m, k.M)) CHECK(std::abs(b) < 1e-9);
  }
  const Case iso = make(12, 0.3, 0, true, 0, 0.01, 0.01);
  for (double b : frame_bending(iso.m, iso.M)) CHECK(b == 0);
}

TEST_CASE("rows along circles: B = h1^2 / (r h2), the same with the domain turned") {
  // centroid radius r in [0.4, 1.6]: B = 0.0025 / 0.005 / r = 0.5 / r
  const Case k = make(48, 0.3, 0, true);
  const std::vector<double> B = frame_bending(k.m, k.M);
  int checked = 0;
  double worst = 0, worst_inside = 0;
  for (int c = 0; c < k.m.num_cells(); ++c) {
    const double r = cell_centroid(k.m, c).norm();
    const int i = c % 48, j = c / 48;
    const double e = std::abs(B[c] * r / 0.5 - 1);
    worst = quadapt_test::worst_of(worst, e);
    if (i > 0 && j > 0 && i < 47 && j < 47) worst_inside = quadapt_test::worst_of(worst_inside, e);
    ++checked;
  }
  CHECK(checked == 48 * 48);
  // least squares of θ over the neighbours one cell (1/48) apart: centred inside, one-sided at the
  // walls (first order, O(h / r))
  CHECK(worst_inside < 0.005);
  CHECK(worst < 0.05);
  const Case turned = make(48, 0.3, 0.7, true);
  const std::vector<double> Bt = frame_bending(turned.m, turned.M);
  for (int c = 0; c < k.m.num_cells(); ++c) CHECK(Bt[c] == doctest::Approx(B[c]).epsilon(1e-9));
  const BendingSummary s = summarize_bending(k.m, k.M, B);
  CHECK(s.max == doctest::Approx(0.5 / (0.3 * std::sqrt(2.0) + std::sqrt(2.0) / 96)).epsilon(0.03));
  CHECK(s.share_over_1 > 0);  // B > 1 where r < 0.5: a few cells at the corner (0.3, 0.3)
  CHECK(s.share_over_1 < 0.01);
  CHECK(s.share_over_2 == 0);
  // stretch 40 instead of 10 (h2 = 0.00125): B four times larger, over 1 where r < 2
  const Case thin = make(48, 0.3, 0, true, 0, 0.05, 0.00125);
  const BendingSummary st = summarize_bending(thin.m, thin.M, frame_bending(thin.m, thin.M));
  CHECK(st.share_over_1 > 0.99);
  CHECK(st.share_over_2 > 0.2);
  CHECK(st.share_over_2 < 0.8);
}
