#include "lpcvt/cell_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace quadapt::lpcvt {

namespace {
/// Relative widening of the boxes against rounding: y is computed as U x in both the build and
/// the search, so only the map of the box's corners back to x and the disk's radius need it.
constexpr double kSlack = 1e-7;
}  // namespace

bool CellGrid::build(const Mat2& G, const Vec2* qv, int nq, double margin, double h, const SiteTree& tree,
                     const std::vector<Vec2>& x, int max_buckets) {
  nx_ = ny_ = 0;
  // G = U^T U, U upper triangular (Cholesky)
  const double u11 = std::sqrt(G(0, 0)), u12 = G(0, 1) / u11, u22 = std::sqrt(G(1, 1) - u12 * u12);
  if (!(u11 > 0 && u22 > 0 && h > 0 && margin >= 0)) return false;
  U_ << u11, u12, 0, u22;
  constexpr double inf = std::numeric_limits<double>::infinity();
  lo_ = Vec2(inf, inf);
  hi_ = Vec2(-inf, -inf);
  for (int k = 0; k < nq; ++k) {
    const Vec2 y = U_ * qv[k];
    lo_ = lo_.cwiseMin(y);
    hi_ = hi_.cwiseMax(y);
  }
  lo_ -= Vec2(margin, margin);
  hi_ += Vec2(margin, margin);
  const double fx = std::ceil((hi_.x() - lo_.x()) / h), fy = std::ceil((hi_.y() - lo_.y()) / h);
  if (!(fx >= 1 && fy >= 1 && fx * fy <= max_buckets)) return false;
  h_ = h;
  // the box's x-space bounds: its corners mapped back by U^-1, widened against rounding
  const Mat2 Ui = U_.inverse();
  Vec2 xlo(inf, inf), xhi(-inf, -inf);
  for (const Vec2& c : {lo_, hi_, Vec2(lo_.x(), hi_.y()), Vec2(hi_.x(), lo_.y())}) {
    const Vec2 p = Ui * c;
    xlo = xlo.cwiseMin(p);
    xhi = xhi.cwiseMax(p);
  }
  const Vec2 w = kSlack * ((xhi - xlo) + xlo.cwiseAbs() + xhi.cwiseAbs());
  tmp_.clear();
  tree.query(xlo - w, xhi + w, tmp_);
  nx_ = static_cast<int>(fx);
  ny_ = static_cast<int>(fy);
  start_.assign(static_cast<size_t>(nx_) * ny_ + 1, 0);
  bucket_.resize(tmp_.size());
  for (size_t k = 0; k < tmp_.size(); ++k) {
    const Vec2 y = U_ * x[tmp_[k]];
    int b = -1;
    if (y.x() >= lo_.x() && y.x() <= hi_.x() && y.y() >= lo_.y() && y.y() <= hi_.y()) {
      const int bx = std::min(nx_ - 1, static_cast<int>((y.x() - lo_.x()) / h_));
      const int by = std::min(ny_ - 1, static_cast<int>((y.y() - lo_.y()) / h_));
      b = by * nx_ + bx;
      ++start_[b + 1];
    }
    bucket_[k] = b;
  }
  for (size_t b = 1; b < start_.size(); ++b) start_[b] += start_[b - 1];
  site_.resize(start_.back());
  at_.assign(start_.begin(), start_.end() - 1);  // each bucket's sites in the answer's (tree) order
  for (size_t k = 0; k < bucket_.size(); ++k)
    if (bucket_[k] >= 0) site_[at_[bucket_[k]]++] = tmp_[k];
  return true;
}

bool CellGrid::candidates(const Vec2& xc, double r, std::vector<int>& out) const {
  if (nx_ == 0) return false;
  const Vec2 yc = U_ * xc;
  const double rr = r * (1 + kSlack) + kSlack * (std::abs(yc.x()) + std::abs(yc.y()));
  if (!(yc.x() - rr >= lo_.x() && yc.x() + rr <= hi_.x() && yc.y() - rr >= lo_.y() && yc.y() + rr <= hi_.y()))
    return false;
  const int bx0 = std::max(0, static_cast<int>((yc.x() - rr - lo_.x()) / h_));
  const int bx1 = std::min(nx_ - 1, static_cast<int>((yc.x() + rr - lo_.x()) / h_));
  const int by0 = std::max(0, static_cast<int>((yc.y() - rr - lo_.y()) / h_));
  const int by1 = std::min(ny_ - 1, static_cast<int>((yc.y() + rr - lo_.y()) / h_));
  for (int by = by0; by <= by1; ++by) {
    const int* b = site_.data() + start_[by * nx_ + bx0];
    const int* e = site_.data() + start_[by * nx_ + bx1 + 1];
    out.insert(out.end(), b, e);
  }
  return true;
}

}  // namespace quadapt::lpcvt
