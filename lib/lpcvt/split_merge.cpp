#include "lpcvt/split_merge.hpp"

#include <algorithm>
#include <map>
#include <set>

#include "lpcvt/boundary_points.hpp"
#include "lpcvt/delaunay.hpp"
#include "lpcvt/rvd.hpp"
#include "mesh/mesh.hpp"

namespace quadapt::lpcvt {

namespace {
/// Work split into fixed blocks of sites (the same blocks for any thread count), each with its
/// own point-location hint.
constexpr int kBlock = 4096;
}  // namespace

int remove_outside(const Background& bg, std::vector<Vec2>& sites, int nfixed) {
  const int n = static_cast<int>(sites.size());
  // free sites outside the domain (or not finite), in fixed blocks each with its own hint
  std::vector<char> drop(n, 0);
  const int nb = (n + kBlock - 1) / kBlock;
#pragma omp parallel for schedule(dynamic, 1) if (n >= 4 * kBlock)
  for (int b = 0; b < nb; ++b) {
    int hint = -1;
    for (int i = std::max(nfixed, b * kBlock); i < std::min(n, (b + 1) * kBlock); ++i) {
      const int c = sites[i].allFinite() ? bg.locate(sites[i], hint) : -1;
      if (c < 0) drop[i] = 1;
      else hint = c;
    }
  }
  // then a site that coincides exactly with an earlier one (the Delaunay graph's "hidden"
  // sites): the others sorted by (x, y, index), each compared with the one before (a copy of a
  // dropped site is outside too)
  std::vector<int> order;
  order.reserve(n);
  for (int i = 0; i < n; ++i)
    if (!drop[i]) order.push_back(i);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    const Vec2 &p = sites[a], &q = sites[b];
    return p.x() != q.x() ? p.x() < q.x() : p.y() != q.y() ? p.y() < q.y() : a < b;
  });
  for (size_t k = 1; k < order.size(); ++k)
    if (sites[order[k]] == sites[order[k - 1]]) drop[order[k]] = 1;
  std::vector<Vec2> kept(sites.begin(), sites.begin() + nfixed);
  int removed = 0;
  for (int i = nfixed; i < n; ++i) {
    if (drop[i]) ++removed;
    else kept.push_back(sites[i]);
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

namespace {

struct MeasuredEdge {
  int i, j;
  double L;
};

/// True when the chord between boundary sites a and b runs along the boundary: its midpoint lies
/// closer to the boundary polyline (the segments' endpoints in `sites`) than kAlongBoundary
/// times the chord's length. A wall that is straight but oblique to the axes has its points on
/// the line only up to rounding, so the Delaunay graph may join two of them across a third (a
/// sliver along the wall); splitting that chord would put a free site on the wall, where its cell
/// is a sliver that the minimisation never moves off. A chord across the domain is kept: a corner
/// cut (at 90 degrees its midpoint is 0.35 of its length from the walls with equal legs, 0.21
/// with legs 1 : 2 as on the eq. 6.1 saddle's corners, 0.05 with 1 : 10) or a narrow channel. A
/// chord of a curved wall is skipped when the wall's radius exceeds 2.5 chords (sagitta = chord^2
/// / (8 radius)): its midpoint would be a free site that close to the wall.
bool along_boundary(const Vec2& a, const Vec2& b, const std::vector<Vec2>& sites,
                    const std::vector<std::array<int, 2>>& boundary_segments) {
  constexpr double kAlongBoundary = 0.05;
  const Vec2 m = 0.5 * (a + b);
  const double lim = kAlongBoundary * (b - a).norm();
  for (const auto& s : boundary_segments)
    if (segment_distance(m, sites[s[0]], sites[s[1]]) < lim) return true;
  return false;
}

/// The Delaunay edges of `sites` measured by eq. 4.12: boundary segments, chords between
/// boundary sites that run along the boundary (along_boundary) and edges whose midpoint is
/// outside the domain skipped; with opt.metric_delaunay only edges that are also Delaunay in the
/// local metric.
std::vector<MeasuredEdge> measure_edges(const Background& bg, const std::vector<Vec2>& sites, int nfixed,
                                        const std::vector<std::array<int, 2>>& boundary_segments,
                                        const SplitMergeOptions& opt) {
  std::set<std::pair<int, int>> bseg;
  for (auto s : boundary_segments) bseg.insert({std::min(s[0], s[1]), std::max(s[0], s[1])});
  // an edge between two boundary sites: measured only when it is not a boundary segment and
  // crosses the domain
  auto skip_fixed = [&](int i, int j) {
    return i < nfixed && j < nfixed &&
           (bseg.count({std::min(i, j), std::max(i, j)}) || along_boundary(sites[i], sites[j], sites, boundary_segments));
  };
  DelaunayGraph dt(sites);
  std::vector<MeasuredEdge> out;
  int hint = -1;
  if (bg.metric_cells()) {
    // metric cells: the edges of the metric Delaunay graph (the neighbours the energy uses)
    MetricGraph g = build_metric_graph(bg, sites, dt);
    // in fixed blocks of sites, in parallel; the blocks' edges joined in order (the serial order)
    const int n = g.num_sites(), nb = (n + kBlock - 1) / kBlock;
    std::vector<std::vector<MeasuredEdge>> part(nb);
#pragma omp parallel for schedule(dynamic, 1) if (n >= 4 * kBlock)
    for (int b = 0; b < nb; ++b) {
      int h = -1;
      for (int i = b * kBlock; i < std::min(n, (b + 1) * kBlock); ++i)
        for (const int* jp = g.nbr_begin(i); jp != g.nbr_end(i); ++jp) {
          const int j = *jp;
          if (j <= i) continue;
          if (skip_fixed(i, j)) continue;
          const int cm = bg.locate(0.5 * (sites[i] + sites[j]), h);
          if (cm < 0) continue;
          h = cm;
          const double L = segment_metric_length(bg, sites[i], sites[j], opt.q, opt.samples);
          if (L >= 0) part[b].push_back({i, j, L});
        }
    }
    for (const auto& p : part) out.insert(out.end(), p.begin(), p.end());
    return out;
  }
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
  for (auto e : dt.edges()) {
    const int i = e[0], j = e[1];
    if (skip_fixed(i, j)) continue;
    const Vec2 mid = 0.5 * (sites[i] + sites[j]);
    const int cm = bg.locate(mid, hint);
    if (cm < 0) continue;
    hint = cm;
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
    out.push_back({i, j, L});
  }
  return out;
}

struct Change {
  double badness;
  int i, j;
  bool split;
};

/// Applies the changes in order, each site touched once; returns (splits, merges).
std::pair<int, int> apply_changes(std::vector<Vec2>& sites, int nfixed, const std::vector<Change>& cands,
                                  int limit) {
  const int n = static_cast<int>(sites.size());
  std::vector<char> flag(n, 0), dead(n, 0);
  std::vector<Vec2> added;
  int splits = 0, merges = 0;
  for (const Change& c : cands) {
    if (splits + merges >= limit) break;
    if (flag[c.i] || flag[c.j]) continue;
    flag[c.i] = flag[c.j] = 1;
    const Vec2 mid = 0.5 * (sites[c.i] + sites[c.j]);
    if (c.split) {
      added.push_back(mid);
      ++splits;
    } else {
      if (c.i >= nfixed && c.j >= nfixed) {
        dead[c.i] = dead[c.j] = 1;
        added.push_back(mid);
      } else {
        dead[c.i >= nfixed ? c.i : c.j] = 1;  // keep the fixed boundary site
      }
      ++merges;
    }
  }
  std::vector<Vec2> out;
  out.reserve(n + added.size());
  for (int i = 0; i < n; ++i)
    if (!dead[i]) out.push_back(sites[i]);
  out.insert(out.end(), added.begin(), added.end());
  sites.swap(out);
  return {splits, merges};
}

}  // namespace

SplitMergeResult split_merge(const Background& bg, std::vector<Vec2>& sites, int nfixed,
                             const std::vector<std::array<int, 2>>& boundary_segments,
                             const SplitMergeOptions& opt) {
  SplitMergeResult r;
  r.removed_outside = remove_outside(bg, sites, nfixed);
  std::vector<MeasuredEdge> edges = measure_edges(bg, sites, nfixed, boundary_segments, opt);
  std::vector<Change> cands;
  double sum = 0;
  r.min_length = 1e300;
  r.max_length = 0;
  for (const MeasuredEdge& e : edges) {
    const double L = e.L;
    ++r.edges;
    sum += L;
    r.min_length = std::min(r.min_length, L);
    r.max_length = std::max(r.max_length, L);
    if (L > opt.lmax)
      cands.push_back({L / opt.lmax, e.i, e.j, true});
    else if (L < opt.lmin && !(e.i < nfixed && e.j < nfixed))
      cands.push_back({opt.lmin / std::max(L, 1e-300), e.i, e.j, false});
  }
  r.mean_length = r.edges ? sum / r.edges : 0;
  if (!r.edges) r.min_length = 0;
  std::stable_sort(cands.begin(), cands.end(), [](const Change& a, const Change& b) { return a.badness > b.badness; });
  auto [s, m] = apply_changes(sites, nfixed, cands, static_cast<int>(sites.size()) + 1);
  r.splits = s;
  r.merges = m;
  return r;
}

int adjust_count(const Background& bg, std::vector<Vec2>& sites, int nfixed,
                 const std::vector<std::array<int, 2>>& boundary_segments, int target,
                 const SplitMergeOptions& opt) {
  int change = 0;
  remove_outside(bg, sites, nfixed);
  for (int pass = 0; pass < 8; ++pass) {
    const int diff = target - static_cast<int>(sites.size());
    if (diff == 0) break;
    std::vector<MeasuredEdge> edges = measure_edges(bg, sites, nfixed, boundary_segments, opt);
    std::vector<Change> cands;
    for (const MeasuredEdge& e : edges) {
      if (diff > 0) cands.push_back({e.L, e.i, e.j, true});
      else if (!(e.i < nfixed && e.j < nfixed)) cands.push_back({1 / std::max(e.L, 1e-300), e.i, e.j, false});
    }
    std::stable_sort(cands.begin(), cands.end(), [](const Change& a, const Change& b) { return a.badness > b.badness; });
    auto [s, m] = apply_changes(sites, nfixed, cands, std::abs(diff));
    if (s + m == 0) break;
    change += s - m;
  }
  return change;
}

}  // namespace quadapt::lpcvt
