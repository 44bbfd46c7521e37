#pragma once
// Point location in a 2D mesh by a uniform grid of buckets over the cells' bounding boxes
// (about one cell per bucket). Exact point-in-polygon test on the straight-sided cells.
// A graded mesh piles many small cells into few buckets (a boundary layer's thin cells: hundreds
// per bucket): a bucket listing more than kCrowded cells gets its own n x n grid of sub-buckets
// (n = ceil(sqrt(count)), capped at 64), each listing, in ascending order, the bucket's cells
// whose bounding box meets it. The answer is the same cell as without the sub-grid (the first
// cell, by index, of x's bucket that contains x: every such cell's box meets x's sub-bucket).
#include <vector>

#include "mesh/mesh.hpp"

namespace quadapt {

class CellLocator {
 public:
  explicit CellLocator(const Mesh& m);
  /// A cell containing x (on a shared edge: one of them), or -1 when x is outside the mesh.
  int locate(const Vec2& x) const;
  /// Every cell containing x (closed cells: on a shared edge both, at a shared vertex all), in
  /// ascending order, into `out` (cleared first).
  void locate_all(const Vec2& x, std::vector<int>& out) const;
  /// The cell containing x, else the cell whose boundary is nearest to x.
  int locate_or_nearest(const Vec2& x) const;
  /// Whether x lies in cell c's interior away from its edges: at a distance above 1e-9 times each
  /// edge's length from its line (a counter-clockwise convex cell). Such a point lies in no other
  /// cell of a conforming mesh, so a caller that remembers the cell of a point that moves a
  /// little (a node between sweeps) can keep it without locate(), for the same answer.
  bool well_inside(int c, const Vec2& x) const;

 private:
  const Mesh& m_;
  Vec2 lo_, cell_size_;
  int nx_ = 1, ny_ = 1;
  std::vector<std::vector<int>> buckets_;
  static constexpr int kCrowded = 16;
  struct Sub {
    int n = 0;         ///< n x n sub-buckets over the bucket's box
    size_t first = 0;  ///< its first sub-bucket in sub_
    Vec2 lo, size;     ///< the bucket's lower corner and a sub-bucket's size
    int index(const Vec2& x, int axis) const;  ///< x's sub-bucket column (axis 0) or row (1), clamped
  };
  std::vector<int> bucket_sub_;  ///< per bucket: index into subs_, or -1
  std::vector<Sub> subs_;
  std::vector<std::vector<int>> sub_;
  /// The cells to test for x in bucket b (its sub-bucket's when it has a sub-grid).
  const std::vector<int>& candidates(size_t b, const Vec2& x) const;
  /// The cells to test for x (its bucket's, as above), or null when x lies outside the grid.
  const std::vector<int>* candidates_of(const Vec2& x) const;
  bool inside(int c, const Vec2& x) const;
  double distance(int c, const Vec2& x) const;
  int bx(double x) const;
  int by(double y) const;
};

}  // namespace quadapt
