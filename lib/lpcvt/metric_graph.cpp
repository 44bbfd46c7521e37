#include "lpcvt/metric_graph.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_set>

namespace quadapt::lpcvt {

namespace {

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

using Tris = std::vector<std::array<int, 3>>;

int index_of(const std::array<int, 3>& a, int x) { return a[0] == x ? 0 : a[1] == x ? 1 : 2; }

}  // namespace

double metric_incircle(const Eigen::Matrix2d& M, const Vec2& a, const Vec2& b, const Vec2& c,
                       const Vec2& d) {
  const Vec2 md = M * d;
  const Vec2 pa = M * a - md, pb = M * b - md, pc = M * c - md;
  const double la = pa.squaredNorm(), lb = pb.squaredNorm(), lc = pc.squaredNorm();
  const double det = la * cross2(pb, pc) - lb * cross2(pa, pc) + lc * cross2(pa, pb);
  const double s = (la + lb + lc) / 3;
  if (!(s > 0)) return 0;
  // a reflection (det M < 0, same metric M^T M; most of PHiLiP's frames) maps the CCW triangle to
  // a CW one and would flip the sign of the test: every flip anti-Delaunay
  return (M(0, 0) * M(1, 1) - M(0, 1) * M(1, 0) < 0 ? -det : det) / (s * s);
}

namespace {

/// The flip rule's test of edge k of triangle t (vertices V[t], neighbours N[t]: N[t][k] across
/// the edge opposite V[t][k]) against its neighbour u = N[t][k]: flip? (Without the "never
/// re-made" rule and the cap, which the Lawson loop applies.)
bool wants_flip(const std::vector<Vec2>& x, const Tris& V, const Tris& N, int t, int k, const EdgeMetric& metric) {
  const int u = N[t][k];
  if (u < 0) return false;
  const int c = V[t][k], p = V[t][(k + 1) % 3], q = V[t][(k + 2) % 3];
  const int l = index_of(N[u], t);
  if (N[u][l] != t) return false;
  const int d = V[u][l];
  if (V[u][(l + 1) % 3] != q || V[u][(l + 2) % 3] != p) return false;
  const Eigen::Matrix2d M = metric({x[c], x[p], x[d], x[q]});
  if (!(metric_incircle(M, x[c], x[p], x[q], x[d]) > 1e-9)) return false;
  // strictly convex quadrilateral c p d q: both new triangles positive (relative to size)
  const double s = (x[d] - x[c]).squaredNorm();
  return cross2(x[p] - x[c], x[d] - x[c]) > 1e-12 * s && cross2(x[d] - x[c], x[q] - x[c]) > 1e-12 * s;
}

/// Lawson flips of g's triangles (g.tris, with their adjacency g.tnb) in place by the flip rule
/// (header), then g's neighbour lists; g's buffers are reused (no allocation once they are large
/// enough: an evaluation of the energy carries the graph and calls this every time).
void flip_and_list(const std::vector<Vec2>& x, MetricGraph& g, const EdgeMetric& metric,
                   const EdgeMetricFactory& parallel_metric) {
  const int n = static_cast<int>(x.size());
  Tris& V = g.tris;
  Tris& N = g.tnb;
  const int nt = static_cast<int>(V.size());
  g.flips = 0;
  g.capped = false;
  MetricGraph::Scratch& w = g.scratch;
  // Edge stack, seeded with every interior edge once (t < neighbour), in triangle order
  // (deterministic: popped from triangle 0 up).
  std::vector<std::pair<int, int>>& stack = w.stack;
  stack.clear();
  // With a metric factory the first test of every edge is made in parallel (fixed blocks of
  // triangles, one fresh metric per block: the same answers for any thread count) and only the
  // edges that want a flip are stacked, in the serial seed's order. An edge that passed may be
  // asked again after a flip nearby: the four outer edges of every flipped quadrilateral are
  // stacked anyway, and no other edge's test can change. The serial loop then pops only the
  // flips and their consequences instead of every edge (1.1e6 points: 3.3 million edges an
  // evaluation, a few thousand flips).
  size_t ninit = 0;
  if (parallel_metric) {
    constexpr int kBlock = 4096;
    const int nblocks = (nt + kBlock - 1) / kBlock;
    std::vector<std::vector<std::pair<int, int>>>& part = w.part;
    if (static_cast<int>(part.size()) < nblocks) part.resize(nblocks);
#pragma omp parallel for schedule(dynamic, 1) if (nblocks > 4)
    for (int b = 0; b < nblocks; ++b) {
      const EdgeMetric m = parallel_metric();
      std::vector<std::pair<int, int>>& out = part[b];
      out.clear();
      for (int t = std::min(nt, (b + 1) * kBlock) - 1; t >= b * kBlock; --t)
        for (int k = 2; k >= 0; --k)
          if (N[t][k] > t && wants_flip(x, V, N, t, k, m)) out.emplace_back(t, k);
    }
    for (int b = nblocks - 1; b >= 0; --b) stack.insert(stack.end(), part[b].begin(), part[b].end());
    ninit = stack.size();
  } else {
    for (int t = nt - 1; t >= 0; --t)
      for (int k = 2; k >= 0; --k)
        if (N[t][k] > t) stack.emplace_back(t, k);
  }
  std::vector<char>& flipped = w.flipped;
  flipped.assign(parallel_metric ? nt : 0, 0);
  const long cap = kMaxFlipsPerSite * std::max(n, 1);
  auto edge_key = [n](int a, int b) { return static_cast<long long>(std::min(a, b)) * n + std::max(a, b); };
  std::unordered_set<long long>& removed = w.removed;
  removed.clear();
  while (!stack.empty()) {
    const size_t entry = stack.size() - 1;
    auto [t, k] = stack.back();
    stack.pop_back();
    const int u = N[t][k];
    if (u < 0) continue;
    // `entry` is a stack position: one below ninit is a seed that wanted a flip, unless it has
    // been reused by an entry pushed after a flip — but those are edges of the flipped triangles
    // t, u only, so `flipped` rejects them (pushing an edge of an unflipped neighbour would need
    // its own mark)
    const bool known = entry < ninit && !flipped[t] && !flipped[u];
    if (!known && !wants_flip(x, V, N, t, k, metric)) continue;
    const int c = V[t][k], p = V[t][(k + 1) % 3], q = V[t][(k + 2) % 3];
    const int l = index_of(N[u], t);
    const int d = V[u][l];
    // an edge removed by a flip is never made again: with a metric that varies, Lawson's flips
    // have no potential that decreases and can cycle (an S-shock frame, 1668 triangles: 39,680
    // flips until the cap); with a constant metric no removed edge is ever made again anyway
    if (removed.count(edge_key(c, d))) continue;
    if (g.flips >= cap) {
      g.capped = true;
      break;
    }
    const int A = N[t][(k + 1) % 3], B = N[t][(k + 2) % 3];
    const int C = N[u][(l + 1) % 3], D = N[u][(l + 2) % 3];
    V[t] = {c, p, d};
    N[t] = {C, u, B};
    V[u] = {c, d, q};
    N[u] = {D, A, t};
    if (C >= 0) N[C][index_of(N[C], u)] = t;
    if (A >= 0) N[A][index_of(N[A], t)] = u;
    removed.insert(edge_key(p, q));
    if (!flipped.empty()) flipped[t] = flipped[u] = 1;
    ++g.flips;
    // the four outer edges may now fail the test
    stack.emplace_back(t, 0);
    stack.emplace_back(t, 2);
    stack.emplace_back(u, 0);
    stack.emplace_back(u, 1);
  }
  // neighbour lists (CSR, sorted): every edge once, from the triangle with the smaller index (or
  // its only one on the hull)
  g.ptr.assign(n + 1, 0);
  auto owns = [&](int t, int k) {  // edge v[k] -> v[k+1] of t, opposite v[k+2]
    const int u = N[t][(k + 2) % 3];
    return u < 0 || t < u;
  };
  // counted and filled in parallel (atomic slots): the order within a list depends on the
  // threads' timing, but every list is sorted below, so the result does not
  const bool par = nt >= 100000;
#pragma omp parallel for schedule(static) if (par)
  for (int t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k)
      if (owns(t, k)) {
#pragma omp atomic
        ++g.ptr[V[t][k] + 1];
#pragma omp atomic
        ++g.ptr[V[t][(k + 1) % 3] + 1];
      }
  for (int i = 0; i < n; ++i) g.ptr[i + 1] += g.ptr[i];
  g.adj.resize(g.ptr[n]);
  {
    std::vector<int>& fill = w.fill;
    fill.assign(g.ptr.begin(), g.ptr.end() - 1);
#pragma omp parallel for schedule(static) if (par)
    for (int t = 0; t < nt; ++t)
      for (int k = 0; k < 3; ++k)
        if (owns(t, k)) {
          const int a = V[t][k], b = V[t][(k + 1) % 3];
          int ia, ib;
#pragma omp atomic capture
          ia = fill[a]++;
#pragma omp atomic capture
          ib = fill[b]++;
          g.adj[ia] = b;
          g.adj[ib] = a;
        }
  }
  // sorted (in parallel: each list on its own); duplicates (only where the input has an edge
  // without a matching twin) removed
  long dup = 0;
#pragma omp parallel for schedule(static) reduction(+ : dup) if (n >= 50000)
  for (int i = 0; i < n; ++i) {
    const int b = g.ptr[i], e = g.ptr[i + 1];
    std::sort(g.adj.begin() + b, g.adj.begin() + e);
    for (int k = b + 1; k < e; ++k) dup += g.adj[k] == g.adj[k - 1];
  }
  if (dup > 0) {
    int out = 0;
    for (int i = 0; i < n; ++i) {
      const int b = g.ptr[i], e = g.ptr[i + 1];
      g.ptr[i] = out;
      for (int k = b; k < e; ++k)
        if (k == b || g.adj[k] != g.adj[k - 1]) g.adj[out++] = g.adj[k];
    }
    g.ptr[n] = out;
    g.adj.resize(out);
  }
}

}  // namespace

MetricGraph metric_delaunay(const std::vector<Vec2>& x, std::vector<std::array<int, 3>> tris,
                            const EdgeMetric& metric, const EdgeMetricFactory& parallel_metric) {
  const int n = static_cast<int>(x.size());
  const int nt = static_cast<int>(tris.size());
  MetricGraph g;
  g.tnb.assign(nt, {-1, -1, -1});
  {
    // triangle adjacency from the outgoing half-edges of every vertex (CSR; no hashing)
    std::vector<int> hptr(n + 1, 0), hto(3 * static_cast<size_t>(nt)), hid(3 * static_cast<size_t>(nt));
    for (int t = 0; t < nt; ++t)
      for (int k = 0; k < 3; ++k) ++hptr[tris[t][(k + 1) % 3] + 1];
    for (int i = 0; i < n; ++i) hptr[i + 1] += hptr[i];
    std::vector<int> fill(hptr.begin(), hptr.end() - 1);
    for (int t = 0; t < nt; ++t)
      for (int k = 0; k < 3; ++k) {  // directed edge a -> b of triangle t, opposite v[k]
        const int h = fill[tris[t][(k + 1) % 3]]++;
        hto[h] = tris[t][(k + 2) % 3];
        hid[h] = t;
      }
    for (int t = 0; t < nt; ++t)
      for (int k = 0; k < 3; ++k) {
        const int a = tris[t][(k + 2) % 3], b = tris[t][(k + 1) % 3];  // the twin b <- a
        for (int h = hptr[a]; h < hptr[a + 1]; ++h)
          if (hto[h] == b) {
            g.tnb[t][k] = hid[h];
            break;
          }
      }
  }
  g.tris = std::move(tris);
  flip_and_list(x, g, metric, parallel_metric);
  return g;
}

bool metric_delaunay_update(const std::vector<Vec2>& x, MetricGraph& g, const EdgeMetric& metric,
                            int max_inverted, const EdgeMetricFactory& parallel_metric) {
  if (g.num_sites() != static_cast<int>(x.size()) || g.tnb.size() != g.tris.size()) return false;
  const int nt = static_cast<int>(g.tris.size());
  int inverted = 0;
  for (int t = 0; t < nt; ++t) {
    const std::array<int, 3>& v = g.tris[t];
    // triangles no longer counter-clockwise at the new positions: more than allowed, rebuild
    if (!(cross2(x[v[1]] - x[v[0]], x[v[2]] - x[v[0]]) > 0) && ++inverted > max_inverted) return false;
  }
  const long before = g.inverted;
  flip_and_list(x, g, metric, parallel_metric);  // in place
  g.inverted = before + inverted;
  return true;
}

}  // namespace quadapt::lpcvt
