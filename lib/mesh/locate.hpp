#pragma once
// Point location in a 2D mesh by a uniform grid of buckets over the cells' bounding boxes
// (about one cell per bucket). Exact point-in-polygon test on the straight-sided cells.
#include <vector>

#include "mesh/mesh.hpp"

namespace quadapt {

class CellLocator {
 public:
  explicit CellLocator(const Mesh& m);
  /// A cell containing x (on a shared edge: one of them), or -1 when x is outside the mesh.
  int locate(const Vec2& x) const;
  /// The cell containing x, else the cell whose boundary is nearest to x.
  int locate_or_nearest(const Vec2& x) const;

 private:
  const Mesh& m_;
  Vec2 lo_, cell_size_;
  int nx_ = 1, ny_ = 1;
  std::vector<std::vector<int>> buckets_;
  bool inside(int c, const Vec2& x) const;
  double distance(int c, const Vec2& x) const;
  int bx(double x) const;
  int by(double y) const;
};

}  // namespace quadapt
