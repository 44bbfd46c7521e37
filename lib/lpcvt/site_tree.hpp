#pragma once
// A static 2-d tree over the sites (balanced, median splits; built in O(n log n)) for box
// queries: the security-radius search of the metric cells (rvd.hpp) needs every site within
// an ellipse, which a graph walk cannot guarantee where the frame grades.
#include <array>
#include <vector>

#include "mesh/mesh.hpp"

namespace quadapt::lpcvt {

class SiteTree {
 public:
  SiteTree() = default;
  explicit SiteTree(const std::vector<Vec2>& sites);
  /// Appends to `out` the indices of the sites in the closed box [lo, hi], in tree order: the
  /// restriction of one fixed order of all sites (the tree's pre-order: node, lower half, upper
  /// half) to the box, so the sites of a smaller box come in the same relative order. Thread-safe.
  void query(const Vec2& lo, const Vec2& hi, std::vector<int>& out) const;
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
  void build(const std::vector<Vec2>& x, int b, int e, int depth);
  /// Bounds of the sites in [b, e) (x: min, max; y: min, max); sets split_ of its nodes.
  std::array<double, 4> fit(int b, int e, int depth);
};

}  // namespace quadapt::lpcvt
