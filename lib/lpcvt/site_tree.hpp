#pragma once
// A static 2-d tree over the sites (balanced, median splits; built in O(n log n)) for box and
// ellipse queries: the security-radius search of the metric cells (rvd.hpp) needs every site
// within an ellipse, which a graph walk cannot guarantee where the frame grades.
#include <array>
#include <vector>

#include "mesh/mesh.hpp"

namespace quadapt::lpcvt {

using Mat2 = Eigen::Matrix2d;  // as lpcvt/background.hpp

class SiteTree {
 public:
  SiteTree() = default;
  explicit SiteTree(const std::vector<Vec2>& sites);
  /// Appends to `out` the indices of the sites in the closed box [lo, hi], in tree order: the
  /// restriction of one fixed order of all sites (the tree's pre-order: node, lower half, upper
  /// half) to the box, so the sites of a smaller box come in the same relative order. Thread-safe.
  void query(const Vec2& lo, const Vec2& hi, std::vector<int>& out) const;
  /// Appends to `out` the indices of a superset of the sites x with (x - c)^T G (x - c) < r2
  /// (G symmetric positive definite), in tree order: the subtrees whose bounding box lies outside
  /// the ellipse are skipped, the others' sites tested (both with kEllipseSlack). For a thin
  /// ellipse oblique to the axes it visits and returns far fewer sites than query() with the
  /// ellipse's box: the box of a 500:1 ellipse at 30 degrees holds ~280x the ellipse's area.
  /// Thread-safe.
  void query_ellipse(const Vec2& c, const Mat2& G, double r2, std::vector<int>& out) const;
  /// Relative widening of the ellipse in query_ellipse against rounding: the quadratic form's
  /// relative rounding error is ~8 eps cond(G), below 1e-2 for cond(G) < 1e13 (a frame's
  /// stretch 1e6 at the metric cells' default anisotropy 0.9 gives cond(G) ~ 6e10).
  static constexpr double kEllipseSlack = 1e-2;
  /// The same sites moved to `sites` (same count and numbering): the tree keeps its arrangement
  /// (so its pre-order) and recomputes, bottom-up in O(n), every node's bounds along its split
  /// axis — the largest coordinate of its lower half, the smallest of its upper half — so that
  /// query() stays exact for any positions; it only prunes less as the halves come to overlap.
  /// A minimisation refits the tree of the last evaluation instead of rebuilding it. Throws
  /// NumericalError when `sites` is not of the tree's size.
  void refit(const std::vector<Vec2>& sites);
  int size() const { return static_cast<int>(idx_.size()); }

 private:
  static constexpr int kParallelSites = 16384;  ///< subtrees at least this large: built as OpenMP tasks
  static constexpr int kLeaf = 8;               ///< ranges of at most this many sites are leaves
  struct Split {
    double lower_max, upper_min;  ///< along the node's axis: bounds of its lower and upper halves
  };
  std::vector<int> idx_;     ///< the sites, arranged as an implicit tree over [0, n)
  std::vector<Vec2> p_;      ///< their positions in the same order (contiguous: the queries read only these)
  std::vector<Split> split_;  ///< per node (indexed by its median position m)
  std::array<double, 4> bounds_{};  ///< of all sites (x: min, max; y: min, max), set by refit
  void build(const std::vector<Vec2>& x, int b, int e, int depth);
  /// Bounds of the sites in [b, e) (x: min, max; y: min, max); sets split_ of its nodes.
  std::array<double, 4> fit(int b, int e, int depth);
};

}  // namespace quadapt::lpcvt
