#include "lpcvt/site_tree.hpp"

#include <algorithm>

namespace quadapt::lpcvt {

SiteTree::SiteTree(const std::vector<Vec2>& sites) : x_(&sites), idx_(sites.size()) {
  for (size_t i = 0; i < sites.size(); ++i) idx_[i] = static_cast<int>(i);
  build(0, static_cast<int>(idx_.size()), 0);
}

void SiteTree::build(int b, int e, int depth) {
  if (e - b <= 8) return;
  const int m = (b + e) / 2, a = depth & 1;
  const std::vector<Vec2>& x = *x_;
  std::nth_element(idx_.begin() + b, idx_.begin() + m, idx_.begin() + e, [&](int i, int j) {
    return x[i][a] != x[j][a] ? x[i][a] < x[j][a] : i < j;
  });
  build(b, m, depth + 1);
  build(m + 1, e, depth + 1);
}

void SiteTree::query(const Vec2& lo, const Vec2& hi, std::vector<int>& out) const {
  if (!idx_.empty()) query(0, static_cast<int>(idx_.size()), 0, lo, hi, out);
}

void SiteTree::query(int b, int e, int depth, const Vec2& lo, const Vec2& hi, std::vector<int>& out) const {
  const std::vector<Vec2>& x = *x_;
  if (e - b <= 8) {
    for (int k = b; k < e; ++k) {
      const Vec2& p = x[idx_[k]];
      if (p.x() >= lo.x() && p.x() <= hi.x() && p.y() >= lo.y() && p.y() <= hi.y()) out.push_back(idx_[k]);
    }
    return;
  }
  const int m = (b + e) / 2, a = depth & 1;
  const Vec2& p = x[idx_[m]];
  if (p.x() >= lo.x() && p.x() <= hi.x() && p.y() >= lo.y() && p.y() <= hi.y()) out.push_back(idx_[m]);
  if (lo[a] <= p[a]) query(b, m, depth + 1, lo, hi, out);
  if (hi[a] >= p[a]) query(m + 1, e, depth + 1, lo, hi, out);
}

}  // namespace quadapt::lpcvt
