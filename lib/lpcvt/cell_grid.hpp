#pragma once
// The sites near one integration cell, bucketed in that cell's metric space: the security-radius
// search of the metric cells (rvd.hpp) for a cell that holds many sites.
//
// Why: in integration cell Q the piece of site i must be clipped by every site j with
// (x_j - x_i)^T G_Q (x_j - x_i) < 4 R^2, an ellipse in x. The site tree answers it with the
// ellipse's axis-aligned box, which for a 10:1 metric at 45 degrees holds ~6x the ellipse's
// sites, and walks ~log2(n / 8) levels for every site: 30 % of lpcvt's CPU at 1.1e5 points. In
// Q's metric space y = U x (G_Q = U^T U) the ellipse is a disk and the sites have about unit
// density (the L_p-CVT spaces them one target edge apart), so a square grid of buckets the size
// of the spacing answers it from the 3 x 3 to 4 x 4 buckets around y_i, ~1 site each.
//
// Exactness: the grid holds every site whose y lies in the covered box [lo, hi] (one site-tree
// query of the box's x-space bounds, then the exact test in y), and candidates() answers only a
// disk inside that box; any other site is outside the disk. So the sites a search keeps (those
// that pass the exact ellipse test in x) are the site tree's, whatever path finds them.
#include <vector>

#include "lpcvt/background.hpp"
#include "lpcvt/site_tree.hpp"

namespace quadapt::lpcvt {

class CellGrid {
 public:
  /// Buckets the sites x whose y = U x lies in the y-bounds of the polygon qv[0..nq) widened
  /// by `margin` on every side (y units), in square buckets of side h; G = U^T U symmetric
  /// positive definite (2 x 2). false (the grid is then empty) when that needs more than
  /// `max_buckets` buckets, or G is not positive definite, or h <= 0 or margin < 0.
  bool build(const Mat2& G, const Vec2* qv, int nq, double margin, double h, const SiteTree& tree,
             const std::vector<Vec2>& x, int max_buckets);
  /// Appends to `out` every site in the buckets that the disk |U (y' - xc)| <= r touches (a
  /// superset of the sites in the disk, in bucket order) and returns true; false, nothing
  /// appended, when the disk (widened by a rounding margin) is not inside the covered box.
  bool candidates(const Vec2& xc, double r, std::vector<int>& out) const;
  bool empty() const { return nx_ == 0; }

 private:
  Mat2 U_ = Mat2::Identity();  ///< y = U x, G = U^T U (upper triangular)
  Vec2 lo_ = Vec2::Zero(), hi_ = Vec2::Zero();  ///< the covered y-box
  double h_ = 1;
  int nx_ = 0, ny_ = 0;
  std::vector<int> start_;  ///< CSR over the buckets (row-major, x fastest): nx * ny + 1
  std::vector<int> site_;   ///< the sites, bucket after bucket
  std::vector<int> tmp_;    ///< the tree query's answer (kept: no allocation per build)
  std::vector<int> bucket_; ///< per answer: its bucket, or -1 (outside the box)
  std::vector<int> at_;     ///< the buckets' fill positions
};

}  // namespace quadapt::lpcvt
