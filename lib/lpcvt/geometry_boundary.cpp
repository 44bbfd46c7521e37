#include "lpcvt/geometry_boundary.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "core/error.hpp"
#include "mesh/boundary.hpp"

namespace quadapt::lpcvt {

namespace {

/// The metric at points of the plane: inside the background its own, outside it
/// the metric of the nearest boundary cell (within a quarter of its boundary
/// edge).
class MetricLookup {
 public:
  explicit MetricLookup(const Background& bg) : bg_(bg) {
    for (const auto& e : free_edges(bg.mesh(), false)) {
      Edge f;
      f.a = bg.mesh().nodes[e[0]];
      f.b = bg.mesh().nodes[e[1]];
      const Vec2 d = f.b - f.a;
      const Vec2 inward(-d.y(), d.x());  // the cell is on the left
      f.cell = bg.locate(0.5 * (f.a + f.b) + 1e-6 * inward, -1);
      if (f.cell >= 0) edges_.push_back(f);
    }
  }
  /// M_eff at y; false when y is too far outside (distance in `dist`).
  bool metric(const Vec2& y, Mat2& M, double& dist) {
    int c = bg_.locate(y, hint_);
    dist = 0;
    if (c >= 0) {
      hint_ = c;
      M = bg_.metric(c, y);
      return true;
    }
    double best = 1e300;
    const Edge* be = nullptr;
    Vec2 proj;
    for (const auto& e : edges_) {
      const Vec2 d = e.b - e.a;
      const double s = std::clamp((y - e.a).dot(d) / d.squaredNorm(), 0.0, 1.0);
      const Vec2 p = e.a + s * d;
      const double r = (y - p).norm();
      if (r < best) {
        best = r;
        be = &e;
        proj = p;
      }
    }
    dist = best;
    if (!be || best > 0.25 * (be->b - be->a).norm()) return false;
    M = bg_.metric(be->cell, proj);
    return true;
  }

 private:
  struct Edge {
    Vec2 a, b;
    int cell = -1;
  };
  const Background& bg_;
  std::vector<Edge> edges_;
  int hint_ = -1;
};

double turn_deg(const Vec2& a, const Vec2& b) {
  const double c = a.dot(b) / (a.norm() * b.norm());
  return std::acos(std::clamp(c, -1.0, 1.0)) * 180 / M_PI;
}

}  // namespace

BoundaryPoints geometry_boundary(const Background& bg, const BoundaryGeometry& g, std::vector<BoundaryGroup>& groups,
                                 double q) {
  groups.clear();
  std::map<std::string, int> group_of;
  for (const auto& name : g.names()) {
    group_of[name] = static_cast<int>(groups.size());
    groups.push_back({static_cast<int>(groups.size()) + 1, name});
  }
  MetricLookup lookup(bg);
  BoundaryPoints out;
  std::map<int, int> vertex_site;
  auto end_site = [&](int v) {
    auto it = vertex_site.find(v);
    if (it != vertex_site.end()) return it->second;
    out.points.push_back(g.vertices()[v]);
    return vertex_site[v] = static_cast<int>(out.points.size()) - 1;
  };
  for (int k = 0; k < g.num_curves(); ++k) {
    const GeometryCurve& cv = g.curves()[k];
    const std::string what = "curve '" + cv.name + "' (" + std::to_string(cv.tag) + ")";
    auto sample = [&](int K, std::vector<double>& t, std::vector<double>& dl, std::vector<Vec2>& tan) {
      t.resize(K + 1);
      dl.resize(K + 1);
      tan.resize(K + 1);
      for (int i = 0; i <= K; ++i) t[i] = cv.t0 + (cv.t1 - cv.t0) * i / K;
      const std::vector<Vec2> x = g.points(k, t);
      for (int i = 0; i <= K; ++i) {
        tan[i] = g.derivative(k, t[i]);
        const Vec2 acc = g.second_derivative(k, t[i]);
        Mat2 M;
        double dist = 0;
        if (!lookup.metric(x[i], M, dist))
          throw InputError(g.source(), what + " passes " + point_text(x[i]) + ", " + std::to_string(dist) +
                                           " outside the frame's domain: the frame is not "
                                           "a mesh of this geometry");
        // sagitta bound: a segment of length h on curvature kappa deviates
        // kappa h^2 / 8 from the curve; at most 1 / kSagittaFactor of the metric's
        // normal spacing 1 / |M n|. Turn bound: a segment of length h turns by kappa h,
        // at most kTargetSegmentTurnDeg, whatever the frame asks (a small hole in a coarse
        // region of the frame)
        const double sp = tan[i].norm();
        const double kappa = sp > 0 ? std::abs(tan[i].x() * acc.y() - tan[i].y() * acc.x()) / (sp * sp * sp) : 0.0;
        const Vec2 n = sp > 0 ? Vec2(-tan[i].y() / sp, tan[i].x() / sp) : Vec2(0, 0);
        dl[i] = std::max({lq_norm(M * tan[i], q), sp * std::sqrt(kSagittaFactor * kappa * (M * n).norm() / 8),
                          sp * kappa / (kTargetSegmentTurnDeg * M_PI / 180)});
      }
    };
    std::vector<double> t, dl;
    std::vector<Vec2> tan;
    auto length = [&](std::vector<double>& C) {
      C.assign(t.size(), 0.0);
      for (size_t i = 1; i < t.size(); ++i) C[i] = C[i - 1] + 0.5 * (dl[i] + dl[i - 1]) * (t[i] - t[i - 1]);
      return C.back();
    };
    std::vector<double> C;
    sample(512, t, dl, tan);
    double L = length(C);
    int n = std::max(cv.closed() ? 3 : 1, static_cast<int>(std::lround(L)));
    if (16 * n > 512) {
      sample(16 * n, t, dl, tan);
      L = length(C);
      n = std::max(cv.closed() ? 3 : 1, static_cast<int>(std::lround(L)));
    }
    out.curve_length.push_back(L);
    out.curve_segments.push_back(n);
    // parameters t_i with L(t_i) = i L / n (eq. 4.7 on the sample interval)
    std::vector<double> tp{cv.t0};
    size_t iv = 1;
    for (int i = 1; i < n; ++i) {
      const double r = i * L / n;
      while (iv + 1 < C.size() && C[iv] < r) ++iv;
      const double h = t[iv] - t[iv - 1], a = dl[iv - 1], rr = r - C[iv - 1];
      const double alpha = h > 0 ? (dl[iv] - dl[iv - 1]) / h : 0.0;
      const double disc = std::sqrt(std::max(0.0, a * a + 2 * alpha * rr));
      const double u = a + disc > 0 ? std::clamp(2 * rr / (a + disc), 0.0, h) : 0.0;
      tp.push_back(t[iv - 1] + u);
    }
    tp.push_back(cv.t1);
    // resolution: the tangent turn within each segment
    size_t j = 0;
    for (int i = 0; i < n; ++i) {
      double turn = 0;
      while (j + 1 < t.size() && t[j + 1] <= tp[i + 1]) {
        if (t[j] >= tp[i]) turn += turn_deg(tan[j], tan[j + 1]);
        ++j;
      }
      if (turn > kMaxSegmentTurnDeg)
        throw InputError(g.source(), what + " turns by " + std::to_string(static_cast<int>(std::lround(turn))) +
                                         " degrees within one of its " + std::to_string(n) + " boundary segments (at most " +
                                         std::to_string(static_cast<int>(kMaxSegmentTurnDeg)) +
                                         "): a corner inside the curve; split the curve at its corners into curves of "
                                         "their own");
    }
    const std::vector<double> inner(tp.begin() + 1, tp.end() - 1);
    const std::vector<Vec2> x = g.points(k, inner);
    std::vector<int> sites;
    if (cv.closed()) {
      out.points.push_back(g.point(k, cv.t0));
      sites.push_back(static_cast<int>(out.points.size()) - 1);
    } else {
      sites.push_back(end_site(cv.ends[0]));
    }
    for (const Vec2& p : x) {
      out.points.push_back(p);
      sites.push_back(static_cast<int>(out.points.size()) - 1);
    }
    sites.push_back(cv.closed() ? sites.front() : end_site(cv.ends[1]));
    for (size_t i = 0; i + 1 < sites.size(); ++i) {
      out.segments.push_back({sites[i], sites[i + 1]});
      out.segment_group.push_back(group_of.at(cv.name));
    }
  }
  return out;
}

}  // namespace quadapt::lpcvt
