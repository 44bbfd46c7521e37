#pragma once
// Vector work in fixed blocks of entries, in parallel, with results that do not depend on the
// thread count: L-BFGS's two loops, the norms of the stopping rules and the change of variables
// between the energy's evaluations (optimize.cpp). A sum is taken per block and then over the
// blocks in order, so it is the same for any number of threads (and a vector of one block gives
// the serial loop's bits).
#include <algorithm>
#include <vector>

#include <Eigen/Core>

namespace quadapt::lpcvt::blocks {

using Index = Eigen::Index;
constexpr Index kBlock = Index(1) << 15;  ///< entries per block; parallel from 4 blocks on

/// Calls f(b, e) for the blocks [b, e) of [0, n), in parallel when there are 4 or more.
template <class F>
void for_blocks(Index n, F&& f) {
  const Index nb = (n + kBlock - 1) / kBlock;
#pragma omp parallel for schedule(static) if (nb >= 4)
  for (Index k = 0; k < nb; ++k) f(k * kBlock, std::min(n, (k + 1) * kBlock));
}

/// Sum over [0, n) of the blocks' partial sums f(b, e), in block order.
template <class F>
double block_sum(Index n, F&& f) {
  const Index nb = (n + kBlock - 1) / kBlock;
  if (nb <= 1) return n > 0 ? f(Index(0), n) : 0.0;
  std::vector<double> part(nb);
  for_blocks(n, [&](Index b, Index e) { part[b / kBlock] = f(b, e); });
  double s = 0;
  for (double v : part) s += v;
  return s;
}

/// a . b (equal sizes)
inline double dot(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return block_sum(a.size(), [&](Index s, Index e) { return a.segment(s, e - s).dot(b.segment(s, e - s)); });
}
/// |a|^2
inline double sqnorm(const Eigen::VectorXd& a) {
  return block_sum(a.size(), [&](Index s, Index e) { return a.segment(s, e - s).squaredNorm(); });
}
/// y += c x (equal sizes)
inline void axpy(double c, const Eigen::VectorXd& x, Eigen::VectorXd& y) {
  for_blocks(x.size(), [&](Index s, Index e) { y.segment(s, e - s) += c * x.segment(s, e - s); });
}

}  // namespace quadapt::lpcvt::blocks
