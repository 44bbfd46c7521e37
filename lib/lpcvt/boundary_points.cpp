#include "lpcvt/boundary_points.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "core/error.hpp"

namespace quadapt::lpcvt {

double lq_norm(const Vec2& v, double q) {
  if (q == 2) return v.norm();
  double a = std::abs(v.x()), b = std::abs(v.y());
  double m = std::max(a, b);
  if (m == 0) return 0;
  const double s = a / m, t = b / m;
  if (q == 6) {  // the frames' default (q = p = 6): the powers by products (std::pow is ~20x dearer)
    const double s2 = s * s, t2 = t * t;
    return m * std::pow(s2 * s2 * s2 + t2 * t2 * t2, 1.0 / 6);
  }
  return m * std::pow(std::pow(s, q) + std::pow(t, q), 1.0 / q);
}

std::vector<BoundaryCurve> boundary_curves(const Background& bg, double corner_angle_deg) {
  const Mesh& m = bg.mesh();
  const double cos_corner = std::cos(corner_angle_deg * M_PI / 180.0);
  std::vector<BoundaryCurve> curves;
  const int ng = std::max<int>(static_cast<int>(m.groups.size()), 1);
  for (int g = 0; g < ng; ++g) {
    std::vector<int> edges;
    for (int e = 0; e < static_cast<int>(m.boundary.size()); ++e)
      if (m.boundary[e].group == g) edges.push_back(e);
    if (edges.empty()) continue;
    std::map<int, std::vector<int>> inc;  // node -> incident edges of this group
    for (int e : edges) {
      inc[m.boundary[e].v[0]].push_back(e);
      inc[m.boundary[e].v[1]].push_back(e);
    }
    auto other = [&](int e, int n) { return m.boundary[e].v[0] == n ? m.boundary[e].v[1] : m.boundary[e].v[0]; };
    std::map<int, bool> brk;
    for (auto& [n, es] : inc) {
      bool b = es.size() != 2;
      if (!b) {
        Vec2 d1 = m.nodes[n] - m.nodes[other(es[0], n)];
        Vec2 d2 = m.nodes[other(es[1], n)] - m.nodes[n];
        double c = d1.dot(d2) / (d1.norm() * d2.norm());
        b = c < cos_corner;
      }
      brk[n] = b;
    }
    std::map<int, bool> used;
    auto walk = [&](int start, int e0, bool closed) {
      BoundaryCurve cv;
      cv.group = g;
      cv.closed = closed;
      cv.nodes.push_back(start);
      int cur = start, e = e0;
      for (;;) {
        used[e] = true;
        int nx = other(e, cur);
        cv.nodes.push_back(nx);
        if (nx == start || brk[nx]) break;
        int ne = -1;
        for (int f : inc[nx])
          if (!used[f]) ne = f;
        if (ne < 0) break;
        cur = nx;
        e = ne;
      }
      if (cv.nodes.size() >= 2 && cv.nodes.front() == cv.nodes.back()) cv.closed = true;
      curves.push_back(cv);
    };
    for (auto& [n, es] : inc)
      if (brk[n])
        for (int e : es)
          if (!used[e]) walk(n, e, false);
    for (int e : edges) {  // closed loops without corners
      if (used[e]) continue;
      int start = std::min(m.boundary[e].v[0], m.boundary[e].v[1]);
      walk(start, e, true);
    }
  }
  if (curves.empty()) throw InputError("", "the background mesh has no boundary");
  return curves;
}

BoundaryPoints mesh_boundary(const Background& bg, const std::vector<BoundaryCurve>& curves,
                             int samples_per_edge, double q) {
  const Mesh& m = bg.mesh();
  BoundaryPoints out;
  std::map<int, int> node_site;  // background node (curve end) -> site
  auto end_site = [&](int node) {
    auto it = node_site.find(node);
    if (it != node_site.end()) return it->second;
    int s = static_cast<int>(out.points.size());
    out.points.push_back(m.nodes[node]);
    node_site[node] = s;
    return s;
  };
  const int sub = bg.is_analytic() ? std::max(1, samples_per_edge) : 1;
  for (const BoundaryCurve& cv : curves) {
    const int K = static_cast<int>(cv.nodes.size()) - 1;
    std::vector<Vec2> P(K + 1);
    std::vector<double> S(K + 1, 0.0);  // arc length at polyline nodes
    for (int k = 0; k <= K; ++k) P[k] = m.nodes[cv.nodes[k]];
    for (int k = 0; k < K; ++k) S[k + 1] = S[k] + (P[k + 1] - P[k]).norm();
    // samples (s, dL): piecewise linear dL between consecutive samples
    std::vector<double> ss, dl;
    int hint = -1;
    for (int k = 0; k < K; ++k) {
      Vec2 d = P[k + 1] - P[k];
      double len = d.norm();
      if (len <= 0) continue;
      Vec2 tau = d / len;
      int c = bg.locate(0.5 * (P[k] + P[k + 1]), hint);
      if (c < 0) throw InputError("", "boundary edge outside the background mesh");
      hint = c;
      for (int j = 0; j <= sub; ++j) {
        double t = static_cast<double>(j) / sub;
        Vec2 y = P[k] + t * d;
        ss.push_back(S[k] + t * len);
        dl.push_back(lq_norm(bg.metric(c, y) * tau, q));
      }
    }
    std::vector<double> C(ss.size(), 0.0);  // cumulative metric length (eq. 4.3)
    for (size_t i = 1; i < ss.size(); ++i) C[i] = C[i - 1] + 0.5 * (dl[i] + dl[i - 1]) * (ss[i] - ss[i - 1]);
    const double L = C.empty() ? 0 : C.back();
    int n = std::max(cv.closed ? 3 : 1, static_cast<int>(std::lround(L)));
    out.curve_length.push_back(L);
    out.curve_segments.push_back(n);
    auto point_at = [&](double s) {
      int k = static_cast<int>(std::upper_bound(S.begin(), S.end(), s) - S.begin()) - 1;
      k = std::clamp(k, 0, K - 1);
      double len = S[k + 1] - S[k];
      double t = len > 0 ? std::clamp((s - S[k]) / len, 0.0, 1.0) : 0.0;
      return Vec2(P[k] + t * (P[k + 1] - P[k]));
    };
    std::vector<int> sites;
    sites.push_back(end_site(cv.nodes.front()));
    size_t iv = 1;
    for (int i = 1; i < n; ++i) {
      double r = i * L / n;
      while (iv + 1 < C.size() && C[iv] < r) ++iv;
      // eq. 4.7 on [ss[iv-1], ss[iv]]: dL(u) = a + alpha u, integral = a u + alpha u^2 / 2
      double h = ss[iv] - ss[iv - 1];
      double a = dl[iv - 1], rr = r - C[iv - 1];
      double alpha = h > 0 ? (dl[iv] - dl[iv - 1]) / h : 0.0;
      double disc = std::max(0.0, a * a + 2 * alpha * rr);
      double u = (a + std::sqrt(disc)) > 0 ? 2 * rr / (a + std::sqrt(disc)) : 0.0;
      u = std::clamp(u, 0.0, h);
      int s = static_cast<int>(out.points.size());
      out.points.push_back(point_at(ss[iv - 1] + u));
      sites.push_back(s);
    }
    sites.push_back(cv.closed ? sites.front() : end_site(cv.nodes.back()));
    for (size_t i = 0; i + 1 < sites.size(); ++i) {
      out.segments.push_back({sites[i], sites[i + 1]});
      out.segment_group.push_back(cv.group);
    }
  }
  return out;
}

double segment_metric_length(const Background& bg, const Vec2& a, const Vec2& b, double q,
                             int samples) {
  Vec2 d = b - a;
  int hint = -1, inside = 0;
  double sum = 0;
  for (int k = 0; k < samples; ++k) {
    Vec2 y = a + ((k + 0.5) / samples) * d;
    int c = bg.locate(y, hint);
    if (c < 0) continue;
    hint = c;
    ++inside;
    sum += lq_norm(bg.metric(c, y) * d, q);
  }
  return inside ? sum / inside : -1.0;
}

}  // namespace quadapt::lpcvt
