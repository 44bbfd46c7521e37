#include "frame/bending.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>

#include "core/error.hpp"
#include "mesh/topology.hpp"

namespace quadapt {

namespace {
struct Axis {
  double theta = 0, h1 = 0, h2 = 0;
  Vec2 v = Vec2::Zero();
  bool long_axis = false;  ///< stretch >= kMinBendingStretch
};

Axis axis_of(const Mat2& M) {
  // M^T M = V^-T V^-1: the small eigenvalue 1/h1^2 along v, the large one 1/h2^2
  const Eigen::SelfAdjointEigenSolver<Mat2> eig(M.transpose() * M);
  Axis a;
  a.h1 = 1 / std::sqrt(eig.eigenvalues()(0));
  a.h2 = 1 / std::sqrt(eig.eigenvalues()(1));
  a.v = eig.eigenvectors().col(0);
  a.theta = std::atan2(a.v.y(), a.v.x());
  a.long_axis = a.h1 >= kMinBendingStretch * a.h2;
  return a;
}
}  // namespace

std::vector<double> frame_bending(const Mesh& bg, const std::vector<Mat2>& M) {
  const int n = bg.num_cells();
  if (static_cast<int>(M.size()) != n) throw Error("frame_bending: " + std::to_string(M.size()) + " metrics for " +
                                                   std::to_string(n) + " cells");
  std::vector<Axis> ax(n);
  std::vector<Vec2> centre(n);
  for (int c = 0; c < n; ++c) ax[c] = axis_of(M[c]), centre[c] = cell_centroid(bg, c);
  const Topology topo = build_topology(bg);
  std::vector<double> B(n, 0.0);
  for (int c = 0; c < n; ++c) {
    if (!ax[c].long_axis) continue;
    // least squares: (x_j - x_c) . g = θ_j - θ_c (mod π, in (-π/2, π/2])
    Mat2 A = Mat2::Zero();
    Vec2 r = Vec2::Zero();
    int used = 0;
    for (int j : topo.neighbours(c)) {
      if (!ax[j].long_axis) continue;
      double d = ax[j].theta - ax[c].theta;
      d -= M_PI * std::round(d / M_PI);
      const Vec2 x = centre[j] - centre[c];
      A += x * x.transpose();
      r += d * x;
      ++used;
    }
    // two neighbours in line (a strip) leave the gradient across them unknown: no B there
    if (used < 2 || !(std::abs(A.determinant()) > 1e-6 * A.trace() * A.trace())) continue;
    const Vec2 g = A.ldlt().solve(r);
    B[c] = std::abs(g.dot(ax[c].v)) * ax[c].h1 * ax[c].h1 / ax[c].h2;
  }
  return B;
}

BendingSummary summarize_bending(const Mesh& bg, const std::vector<Mat2>& M, const std::vector<double>& B) {
  BendingSummary s;
  double total = 0, over1 = 0, over2 = 0;
  for (int c = 0; c < bg.num_cells(); ++c) {
    const double w = std::abs(cell_area(bg, c) * M[c].determinant()) / 4;
    total += w;
    if (B[c] > 1) over1 += w;
    if (B[c] > 2) over2 += w;
    s.max = std::max(s.max, B[c]);
  }
  if (total > 0) s.share_over_1 = over1 / total, s.share_over_2 = over2 / total;
  return s;
}

}  // namespace quadapt
