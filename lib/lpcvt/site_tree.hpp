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
  /// Appends to `out` the indices of the sites in the closed box [lo, hi] (in tree order:
  /// deterministic). Thread-safe.
  void query(const Vec2& lo, const Vec2& hi, std::vector<int>& out) const;

 private:
  const std::vector<Vec2>* x_ = nullptr;
  std::vector<int> idx_;  ///< the sites, arranged as an implicit tree over [0, n)
  void build(int b, int e, int depth);
  void query(int b, int e, int depth, const Vec2& lo, const Vec2& hi, std::vector<int>& out) const;
};

}  // namespace quadapt::lpcvt
