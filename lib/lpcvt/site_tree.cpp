#include "lpcvt/site_tree.hpp"

#include <algorithm>
#include <array>
#include <limits>

#include <omp.h>

#include "core/error.hpp"

namespace quadapt::lpcvt {

SiteTree::SiteTree(const std::vector<Vec2>& sites) : idx_(sites.size()) {
  for (size_t i = 0; i < sites.size(); ++i) idx_[i] = static_cast<int>(i);
  // the two halves of a split are independent: the top levels' halves as OpenMP tasks (the tree
  // is the same for any thread count)
  const int n = static_cast<int>(idx_.size());
#pragma omp parallel if (n >= kParallelSites && !omp_in_parallel())
#pragma omp single
  build(sites, 0, n, 0);
  refit(sites);
}

void SiteTree::build(const std::vector<Vec2>& x, int b, int e, int depth) {
  if (e - b <= kLeaf) return;
  const int m = (b + e) / 2, a = depth & 1;
  std::nth_element(idx_.begin() + b, idx_.begin() + m, idx_.begin() + e, [&](int i, int j) {
    return x[i][a] != x[j][a] ? x[i][a] < x[j][a] : i < j;
  });
  if (e - b >= kParallelSites) {
#pragma omp task default(shared) firstprivate(b, m, depth)
    build(x, b, m, depth + 1);
    build(x, m + 1, e, depth + 1);
#pragma omp taskwait
  } else {
    build(x, b, m, depth + 1);
    build(x, m + 1, e, depth + 1);
  }
}

void SiteTree::refit(const std::vector<Vec2>& sites) {
  const int n = static_cast<int>(idx_.size());
  if (sites.size() != idx_.size()) throw NumericalError("SiteTree::refit: not the tree's number of sites");
  p_.resize(n);
  split_.resize(n);
#pragma omp parallel for schedule(static) if (n >= kParallelSites && !omp_in_parallel())
  for (int k = 0; k < n; ++k) p_[k] = sites[idx_[k]];
#pragma omp parallel if (n >= kParallelSites && !omp_in_parallel())
#pragma omp single
  bounds_ = fit(0, n, 0);
}

std::array<double, 4> SiteTree::fit(int b, int e, int depth) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  std::array<double, 4> box{inf, -inf, inf, -inf};
  auto add = [&box](const Vec2& p) {
    box[0] = std::min(box[0], p.x());
    box[1] = std::max(box[1], p.x());
    box[2] = std::min(box[2], p.y());
    box[3] = std::max(box[3], p.y());
  };
  if (e - b <= kLeaf) {
    for (int k = b; k < e; ++k) add(p_[k]);
    return box;
  }
  const int m = (b + e) / 2, a = depth & 1;
  std::array<double, 4> lo, hi;
  if (e - b >= kParallelSites) {
#pragma omp task default(shared) firstprivate(b, m, depth)
    lo = fit(b, m, depth + 1);
    hi = fit(m + 1, e, depth + 1);
#pragma omp taskwait
  } else {
    lo = fit(b, m, depth + 1);
    hi = fit(m + 1, e, depth + 1);
  }
  split_[m] = {lo[2 * a + 1], hi[2 * a]};
  add(p_[m]);
  for (const auto& h : {lo, hi}) {
    box[0] = std::min(box[0], h[0]);
    box[1] = std::max(box[1], h[1]);
    box[2] = std::min(box[2], h[2]);
    box[3] = std::max(box[3], h[3]);
  }
  return box;
}

void SiteTree::query(const Vec2& lo, const Vec2& hi, std::vector<int>& out) const {
  // iterative, depth first, the lower half before the upper one: the order of the recursion
  struct Range {
    int b, e, depth;
  };
  Range stack[64];
  int top = 0;
  if (!idx_.empty()) stack[top++] = {0, static_cast<int>(idx_.size()), 0};
  const double lx = lo.x(), ly = lo.y(), hx = hi.x(), hy = hi.y();
  while (top > 0) {
    const Range r = stack[--top];
    if (r.e - r.b <= kLeaf) {
      for (int k = r.b; k < r.e; ++k) {
        const Vec2& p = p_[k];
        if (p.x() >= lx && p.x() <= hx && p.y() >= ly && p.y() <= hy) out.push_back(idx_[k]);
      }
      continue;
    }
    const int m = (r.b + r.e) / 2;
    const Vec2& p = p_[m];
    if (p.x() >= lx && p.x() <= hx && p.y() >= ly && p.y() <= hy) out.push_back(idx_[m]);
    const Split& s = split_[m];
    const bool low = (r.depth & 1 ? ly : lx) <= s.lower_max, high = (r.depth & 1 ? hy : hx) >= s.upper_min;
    if (high) stack[top++] = {m + 1, r.e, r.depth + 1};
    if (low) stack[top++] = {r.b, m, r.depth + 1};
  }
}

namespace {
/// The smallest u^T G u over the box [x0, x1] x [y0, y1] of u (0 when the box holds u = 0): on
/// one of its edges otherwise, where the quadratic in the free coordinate is minimised and clamped.
double box_min(const Mat2& G, double x0, double x1, double y0, double y1) {
  if (x0 <= 0 && 0 <= x1 && y0 <= 0 && 0 <= y1) return 0;
  const double a = G(0, 0), b = G(0, 1), d = G(1, 1);
  double best = std::numeric_limits<double>::infinity();
  for (double ux : {x0, x1}) {
    const double uy = std::clamp(-b * ux / d, y0, y1);
    best = std::min(best, a * ux * ux + 2 * b * ux * uy + d * uy * uy);
  }
  for (double uy : {y0, y1}) {
    const double ux = std::clamp(-b * uy / a, x0, x1);
    best = std::min(best, a * ux * ux + 2 * b * ux * uy + d * uy * uy);
  }
  return best;
}
}  // namespace

void SiteTree::query_ellipse(const Vec2& c, const Mat2& G, double r2, std::vector<int>& out) const {
  // iterative, depth first, the lower half before the upper one (the order of query()); every
  // range carries the bounds of its sites relative to c, narrowed along the split axes
  struct Range {
    int b, e, depth;
    double box[4];  // x: min, max; y: min, max, of u = site - c
  };
  Range stack[64];
  int top = 0;
  if (idx_.empty()) return;
  const double lim = r2 * (1 + kEllipseSlack);
  auto inside = [&](const Vec2& p) {
    const double ux = p.x() - c.x(), uy = p.y() - c.y();
    return G(0, 0) * ux * ux + 2 * G(0, 1) * ux * uy + G(1, 1) * uy * uy < lim;
  };
  stack[top++] = {0, static_cast<int>(idx_.size()), 0,
                  {bounds_[0] - c.x(), bounds_[1] - c.x(), bounds_[2] - c.y(), bounds_[3] - c.y()}};
  while (top > 0) {
    const Range r = stack[--top];
    if (box_min(G, r.box[0], r.box[1], r.box[2], r.box[3]) >= lim) continue;
    if (r.e - r.b <= kLeaf) {
      for (int k = r.b; k < r.e; ++k)
        if (inside(p_[k])) out.push_back(idx_[k]);
      continue;
    }
    const int m = (r.b + r.e) / 2, a = r.depth & 1;
    if (inside(p_[m])) out.push_back(idx_[m]);
    const Split& s = split_[m];
    const double ca = a ? c.y() : c.x();
    Range hi = {m + 1, r.e, r.depth + 1, {r.box[0], r.box[1], r.box[2], r.box[3]}};
    hi.box[2 * a] = std::max(hi.box[2 * a], s.upper_min - ca);
    Range lo = {r.b, m, r.depth + 1, {r.box[0], r.box[1], r.box[2], r.box[3]}};
    lo.box[2 * a + 1] = std::min(lo.box[2 * a + 1], s.lower_max - ca);
    if (m + 1 < r.e) stack[top++] = hi;
    if (r.b < m) stack[top++] = lo;
  }
}

}  // namespace quadapt::lpcvt
