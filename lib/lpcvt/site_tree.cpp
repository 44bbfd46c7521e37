#include "lpcvt/site_tree.hpp"

#include <algorithm>

namespace quadapt::lpcvt {

SiteTree::SiteTree(const std::vector<Vec2>& sites) : idx_(sites.size()) {
  for (size_t i = 0; i < sites.size(); ++i) idx_[i] = static_cast<int>(i);
  build(sites, 0, static_cast<int>(idx_.size()), 0);
  p_.resize(idx_.size());
  for (size_t k = 0; k < idx_.size(); ++k) p_[k] = sites[idx_[k]];
}

void SiteTree::build(const std::vector<Vec2>& x, int b, int e, int depth) {
  if (e - b <= 8) return;
  const int m = (b + e) / 2, a = depth & 1;
  std::nth_element(idx_.begin() + b, idx_.begin() + m, idx_.begin() + e, [&](int i, int j) {
    return x[i][a] != x[j][a] ? x[i][a] < x[j][a] : i < j;
  });
  build(x, b, m, depth + 1);
  build(x, m + 1, e, depth + 1);
}

void SiteTree::query(const Vec2& lo, const Vec2& hi, std::vector<int>& out) const {
  if (!idx_.empty()) query(0, static_cast<int>(idx_.size()), 0, lo, hi, out);
}

void SiteTree::query(int b, int e, int depth, const Vec2& lo, const Vec2& hi, std::vector<int>& out) const {
  if (e - b <= 8) {
    for (int k = b; k < e; ++k) {
      const Vec2& p = p_[k];
      if (p.x() >= lo.x() && p.x() <= hi.x() && p.y() >= lo.y() && p.y() <= hi.y()) out.push_back(idx_[k]);
    }
    return;
  }
  const int m = (b + e) / 2, a = depth & 1;
  const Vec2& p = p_[m];
  if (p.x() >= lo.x() && p.x() <= hi.x() && p.y() >= lo.y() && p.y() <= hi.y()) out.push_back(idx_[m]);
  if (lo[a] <= p[a]) query(b, m, depth + 1, lo, hi, out);
  if (hi[a] >= p[a]) query(m + 1, e, depth + 1, lo, hi, out);
}

}  // namespace quadapt::lpcvt
