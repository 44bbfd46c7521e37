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
  const double det = pa.squaredNorm() * cross2(pb, pc) - pb.squaredNorm() * cross2(pa, pc) +
                     pc.squaredNorm() * cross2(pa, pb);
  const double scale = pa.squaredNorm() * (pc - pb).squaredNorm();  // |M(d - a)|^2 |M(c - b)|^2
  if (!(scale > 0)) return 0;
  // a reflection (det M < 0, same metric M^T M; most of PHiLiP's frames) maps the CCW triangle to
  // a CW one and would flip the sign of the test: every flip anti-Delaunay
  return (M(0, 0) * M(1, 1) - M(0, 1) * M(1, 0) < 0 ? -det : det) / scale;
}

namespace {

/// The flip rule's test of edge k of triangle t (vertices V[t], neighbours N[t]: N[t][k] across
/// the edge opposite V[t][k]) against its neighbour u = N[t][k]: the in-circle value when the
/// edge wants a flip (> 1e-9, the quadrilateral strictly convex), else -1. (Without the "never
/// re-made" rule and the cap, which the Lawson loop applies.)
double flip_value(const std::vector<Vec2>& x, const Tris& V, const Tris& N, int t, int k, const EdgeMetric& metric) {
  const int u = N[t][k];
  if (u < 0) return -1;
  const int c = V[t][k], p = V[t][(k + 1) % 3], q = V[t][(k + 2) % 3];
  const int l = index_of(N[u], t);
  if (N[u][l] != t) return -1;
  const int d = V[u][l];
  if (V[u][(l + 1) % 3] != q || V[u][(l + 2) % 3] != p) return -1;
  const Eigen::Matrix2d M = metric({x[c], x[p], x[d], x[q]});
  const double v = metric_incircle(M, x[c], x[p], x[q], x[d]);
  if (!(v > 1e-9)) return -1;
  // strictly convex quadrilateral c p d q: both new triangles positive (relative to size)
  const double s = (x[d] - x[c]).squaredNorm();
  if (!(cross2(x[p] - x[c], x[d] - x[c]) > 1e-12 * s && cross2(x[d] - x[c], x[q] - x[c]) > 1e-12 * s)) return -1;
  return v;
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
  using Want = MetricGraph::Scratch::Want;
  std::vector<int>& version = w.version;
  version.assign(nt, 0);
  // The edges that want a flip, most violated first (header, "Flip order"): a binary heap on
  // (value, t, k). With a metric factory the first test of every edge (t < its neighbour) is
  // made in parallel (fixed blocks of triangles, one fresh metric per block: the same answers for
  // any thread count); the serial loop then pops only the flips and their consequences instead
  // of every edge (1.1e6 points: 3.3 million edges an evaluation, a few thousand flips).
  auto before = [](const Want& a, const Want& b) {  // heap order: b pops first
    return a.value != b.value ? a.value < b.value : a.t != b.t ? a.t > b.t : a.k > b.k;
  };
  std::vector<Want>& heap = w.heap;
  heap.clear();
  auto test = [&](int t, int k, const EdgeMetric& m, std::vector<Want>& out) {
    const double v = flip_value(x, V, N, t, k, m);
    if (v >= 0) out.push_back({v, t, k, N[t][k], version[t], version[N[t][k]]});
  };
  if (parallel_metric) {
    constexpr int kBlock = 4096;
    const int nblocks = (nt + kBlock - 1) / kBlock;
    std::vector<std::vector<Want>>& part = w.part;
    if (static_cast<int>(part.size()) < nblocks) part.resize(nblocks);
#pragma omp parallel for schedule(dynamic, 1) if (nblocks > 4)
    for (int b = 0; b < nblocks; ++b) {
      const EdgeMetric m = parallel_metric();
      std::vector<Want>& out = part[b];
      out.clear();
      for (int t = b * kBlock; t < std::min(nt, (b + 1) * kBlock); ++t)
        for (int k = 0; k < 3; ++k)
          if (N[t][k] > t) test(t, k, m, out);
    }
    for (int b = 0; b < nblocks; ++b) heap.insert(heap.end(), part[b].begin(), part[b].end());
  } else {
    for (int t = 0; t < nt; ++t)
      for (int k = 0; k < 3; ++k)
        if (N[t][k] > t) test(t, k, metric, heap);
  }
  std::make_heap(heap.begin(), heap.end(), before);
  auto push = [&](int t, int k) {
    const size_t n0 = heap.size();
    test(t, k, metric, heap);
    if (heap.size() > n0) std::push_heap(heap.begin(), heap.end(), before);
  };
  const long cap = kMaxFlipsPerSite * std::max(n, 1);
  auto edge_key = [n](int a, int b) { return static_cast<long long>(std::min(a, b)) * n + std::max(a, b); };
  std::unordered_set<long long>& removed = w.removed;
  removed.clear();
  while (!heap.empty()) {
    std::pop_heap(heap.begin(), heap.end(), before);
    const Want e = heap.back();
    heap.pop_back();
    const int t = e.t, k = e.k, u = N[t][k];
    // an entry made before t, its neighbour or theirs changed: tested again, queued anew
    if (u != e.u || version[t] != e.vt || version[u] != e.vu) {
      push(t, k);
      continue;
    }
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
    // every entry of these six triangles' edges is stale now
    for (int s : {t, u, A, B, C, D})
      if (s >= 0) ++version[s];
    ++g.flips;
    // the four outer edges may now fail the test
    push(t, 0);
    push(t, 2);
    push(u, 0);
    push(u, 1);
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
