#pragma once
// A static 2-d tree over the sites (balanced, median splits; built in O(n log n)) for box
// queries: the security-radius search of the metric cells (rvd.hpp) needs every site within
// an ellipse, which a graph walk cannot guarantee where the frame grades.
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

 private:
  static constexpr int kParallelSites = 16384;  ///< subtrees at least this large: built as OpenMP tasks
  std::vector<int> idx_;  ///< the sites, arranged as an implicit tree over [0, n)
  std::vector<Vec2> p_;   ///< their positions in the same order (contiguous: the queries read only these)
  void build(const std::vector<Vec2>& x, int b, int e, int depth);
};

}  // namespace quadapt::lpcvt
