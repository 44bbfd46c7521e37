#include "lpcvt/split_merge.hpp"

#include <algorithm>
#include <map>
#include <set>

#include "lpcvt/boundary.hpp"
#include "lpcvt/delaunay.hpp"

namespace quadapt::lpcvt {

int remove_outside(const Background& bg, std::vector<Vec2>& sites, int nfixed) {
  DelaunayGraph dt(sites);
  std::vector<Vec2> kept(sites.begin(), sites.begin() + nfixed);
  int removed = 0, hint = -1;
  for (int i = nfixed; i < static_cast<int>(sites.size()); ++i) {
    int c = bg.locate(sites[i], hint);
    if (c < 0 || dt.hidden(i)) {
      ++removed;
      continue;
    }
    hint = c;
    kept.push_back(sites[i]);
  }
  sites.swap(kept);
  return removed;
}

namespace {
/// > 0 when d lies inside the circumcircle of a, b, c (any orientation), relative to the scale.
double incircle(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const Vec2 ad = a - d, bd = b - d, cd = c - d;
  const double det = ad.squaredNorm() * (bd.x() * cd.y() - bd.y() * cd.x()) -
                     bd.squaredNorm() * (ad.x() * cd.y() - ad.y() * cd.x()) +
                     cd.squaredNorm() * (ad.x() * bd.y() - ad.y() * bd.x());
  const double orient = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
  const double scale = std::max({ad.squaredNorm(), bd.squaredNorm(), cd.squaredNorm()});
  return (orient > 0 ? det : -det) / (scale * std::abs(orient) + 1e-300);
}
}  // namespace

SplitMergeResult split_merge(const Background& bg, std::vector<Vec2>& sites, int nfixed,
                             const std::vector<std::array<int, 2>>& boundary_segments,
                             const SplitMergeOptions& opt) {
  SplitMergeResult r;
  r.removed_outside = remove_outside(bg, sites, nfixed);
  const int n = static_cast<int>(sites.size());
  std::set<std::pair<int, int>> bseg;
  for (auto s : boundary_segments) bseg.insert({std::min(s[0], s[1]), std::max(s[0], s[1])});
  DelaunayGraph dt(sites);
  struct Cand {
    double badness;
    int i, j;
    bool split;
  };
  // Opposite vertices of each Delaunay edge, for the metric-Delaunay test.
  std::map<std::pair<int, int>, std::array<int, 2>> opposite;
  if (opt.metric_delaunay) {
    for (const auto& t : dt.triangles())
      for (int k = 0; k < 3; ++k) {
        int a = t[k], b = t[(k + 1) % 3], c = t[(k + 2) % 3];
        auto& o = opposite.try_emplace({std::min(a, b), std::max(a, b)}, std::array<int, 2>{-1, -1}).first->second;
        (o[0] < 0 ? o[0] : o[1]) = c;
      }
  }
  std::vector<Cand> cands;
  double sum = 0;
  r.min_length = 1e300;
  r.max_length = 0;
  for (auto e : dt.edges()) {
    const int i = e[0], j = e[1];
    const bool fi = i < nfixed, fj = j < nfixed;
    if (fi && fj && bseg.count({i, j})) continue;
    const Vec2 mid = 0.5 * (sites[i] + sites[j]);
    const int cm = bg.locate(mid);
    if (cm < 0) continue;
    if (opt.metric_delaunay) {
      auto it = opposite.find({i, j});
      if (it != opposite.end() && it->second[0] >= 0 && it->second[1] >= 0) {
        const Mat2 M = bg.metric(cm, mid);
        const Vec2 a = M * sites[i], b = M * sites[j], c = M * sites[it->second[0]], d = M * sites[it->second[1]];
        if (incircle(a, b, c, d) > 1e-9) continue;  // flipped in the metric: not a metric edge
      }
    }
    double L = segment_metric_length(bg, sites[i], sites[j], opt.q, opt.samples);
    if (L < 0) continue;
    ++r.edges;
    sum += L;
    r.min_length = std::min(r.min_length, L);
    r.max_length = std::max(r.max_length, L);
    if (L > opt.lmax)
      cands.push_back({L / opt.lmax, i, j, true});
    else if (L < opt.lmin && !(fi && fj))
      cands.push_back({opt.lmin / std::max(L, 1e-300), i, j, false});
  }
  r.mean_length = r.edges ? sum / r.edges : 0;
  if (!r.edges) r.min_length = 0;
  std::stable_sort(cands.begin(), cands.end(), [](const Cand& a, const Cand& b) { return a.badness > b.badness; });
  std::vector<char> flag(n, 0), dead(n, 0);
  std::vector<Vec2> added;
  for (const Cand& c : cands) {
    if (flag[c.i] || flag[c.j]) continue;
    flag[c.i] = flag[c.j] = 1;
    const Vec2 mid = 0.5 * (sites[c.i] + sites[c.j]);
    if (c.split) {
      added.push_back(mid);
      ++r.splits;
    } else {
      if (c.i >= nfixed && c.j >= nfixed) {
        dead[c.i] = dead[c.j] = 1;
        added.push_back(mid);
      } else {
        dead[c.i >= nfixed ? c.i : c.j] = 1;  // keep the fixed boundary site
      }
      ++r.merges;
    }
  }
  std::vector<Vec2> out;
  out.reserve(n + added.size());
  for (int i = 0; i < n; ++i)
    if (!dead[i]) out.push_back(sites[i]);
  out.insert(out.end(), added.begin(), added.end());
  sites.swap(out);
  return r;
}

}  // namespace quadapt::lpcvt
