#include "quad/metric_matching.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <lemon/list_graph.h>
#include <lemon/matching.h>

#include <stdexcept>

#include "core/error.hpp"

namespace quadapt {

namespace {

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

}  // namespace

double metric_quad_quality(const Eigen::Matrix2d& F, const Vec2& a, const Vec2& b, const Vec2& c,
                           const Vec2& d, double min_sine) {
  const Vec2 p[4] = {F * a, F * b, F * c, F * d};
  double worst = 0;
  for (int k = 0; k < 4; ++k) {
    const Vec2 u = p[(k + 1) % 4] - p[k], v = p[(k + 3) % 4] - p[k];
    const double cr = cross2(u, v), nu = u.norm(), nv = v.norm();
    if (!(nu > 0) || !(nv > 0) || !(cr > min_sine * nu * nv)) return 0;  // not strictly convex
    const double ang = std::atan2(cr, u.dot(v)) * 180.0 / M_PI;
    worst = std::max(worst, std::abs(ang - 90.0));
  }
  return std::max(0.0, 1.0 - worst / 90.0);
}

Mesh metric_pairing(const Mesh& tri, const std::vector<Eigen::Matrix2d>& M,
                    const MetricMatchingOptions& opt, MetricMatchingStats* stats) {
  const int nt = tri.num_cells();
  if (!M.empty() && static_cast<int>(M.size()) != nt)
    throw InputError("", "metric_pairing: " + std::to_string(M.size()) + " frame matrices for " + std::to_string(nt) +
                             " triangles (one M per triangle: Frame::at_cells(tri))");
  for (const Cell& c : tri.cells)
    if (c.nv != 3) throw InputError("", "metric_pairing: the input must be all triangles (a cell has " + std::to_string(c.nv) + " vertices)");
  // interior edges: (min, max) vertex pair -> the two triangles and their opposite vertices
  struct HalfEdge {
    int a, b, t, opp;
  };
  std::vector<HalfEdge> he;
  he.reserve(static_cast<size_t>(nt) * 3);
  for (int t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = tri.cells[t].v[k], b = tri.cells[t].v[(k + 1) % 3];
      he.push_back({std::min(a, b), std::max(a, b), t, tri.cells[t].v[(k + 2) % 3]});
    }
  std::sort(he.begin(), he.end(), [](const HalfEdge& x, const HalfEdge& y) {
    return x.a != y.a ? x.a < y.a : x.b != y.b ? x.b < y.b : x.t < y.t;
  });
  // triangles with an edge on the boundary (an edge no other triangle shares)
  std::vector<char> wall(nt, 0);
  for (size_t i = 0; i < he.size(); ++i) {
    const bool prev = i > 0 && he[i - 1].a == he[i].a && he[i - 1].b == he[i].b;
    const bool next = i + 1 < he.size() && he[i + 1].a == he[i].a && he[i + 1].b == he[i].b;
    if (!prev && !next) wall[he[i].t] = 1;
  }
  lemon::ListGraph g;
  std::vector<lemon::ListGraph::Node> node(nt);
  for (int t = 0; t < nt; ++t) node[t] = g.addNode();
  lemon::ListGraph::EdgeMap<long> weight(g);
  struct Pair {
    int t1, t2;
    std::array<int, 4> quad;  ///< CCW
    double q;
  };
  std::vector<Pair> pairs;
  lemon::ListGraph::EdgeMap<int> pair_of(g);
  std::vector<Eigen::Matrix2d> G;
  if (!M.empty()) {
    G.resize(nt);
    for (int t = 0; t < nt; ++t) G[t] = M[t].transpose() * M[t];
  }
  for (size_t i = 0; i + 1 < he.size(); ++i) {
    const HalfEdge &x = he[i], &y = he[i + 1];
    if (x.a != y.a || x.b != y.b) continue;
    // triangle x.t = (.., x.a/x.b, .., x.opp); the quad in CCW order: walk x.t's vertices and
    // insert y.opp between the shared edge's endpoints
    const Cell& c = tri.cells[x.t];
    int k0 = 0;
    while (c.v[k0] == x.a || c.v[k0] == x.b) ++k0;  // k0: the opposite vertex of x.t
    const std::array<int, 4> quad = {c.v[k0], c.v[(k0 + 1) % 3], y.opp, c.v[(k0 + 2) % 3]};
    Eigen::Matrix2d F = Eigen::Matrix2d::Identity();
    if (!G.empty()) {
      const Eigen::Matrix2d Gm = 0.5 * (G[x.t] + G[y.t]);
      Eigen::LLT<Eigen::Matrix2d> llt(Gm);
      if (llt.info() != Eigen::Success) continue;
      F = llt.matrixL().transpose();  // |F e|^2 = e^T G e
    }
    const auto& P = tri.nodes;
    // a candidate when strictly convex in physical space (a valid quad), no corner straight up to
    // rounding (kMinPairSine); its metric quality (0 when not convex in the averaged metric) ranks it
    const Eigen::Matrix2d I = Eigen::Matrix2d::Identity();
    if (!(metric_quad_quality(I, P[quad[0]], P[quad[1]], P[quad[2]], P[quad[3]], kMinPairSine) > 0)) continue;
    const double q = metric_quad_quality(F, P[quad[0]], P[quad[1]], P[quad[2]], P[quad[3]]);
    if (opt.min_quality > 0 && !(q > opt.min_quality)) continue;
    auto e = g.addEdge(node[x.t], node[y.t]);
    const int interior = (wall[x.t] ? 0 : 1) + (wall[y.t] ? 0 : 1);
    weight[e] = std::lround(1000.0 * (q + opt.pair_bonus + opt.interior_bonus * interior));
    pair_of[e] = static_cast<int>(pairs.size());
    pairs.push_back({x.t, y.t, quad, q});
  }
  lemon::MaxWeightedMatching<lemon::ListGraph, lemon::ListGraph::EdgeMap<long>> mwm(g, weight);
  mwm.run();
  std::vector<char> used(nt, 0);
  std::vector<int> chosen;
  for (lemon::ListGraph::EdgeIt e(g); e != lemon::INVALID; ++e)
    if (mwm.matching(e)) chosen.push_back(pair_of[e]);
  std::sort(chosen.begin(), chosen.end());
  Mesh out = tri;  // nodes, boundary groups and names; cells rebuilt below, no fields
  out.cells.clear();
  out.clear_fields();
  double qsum = 0;
  for (int k : chosen) {
    const Pair& p = pairs[k];
    if (used[p.t1] || used[p.t2]) throw Error("metric_pairing: a triangle matched twice (internal error)");
    used[p.t1] = used[p.t2] = 1;
    Cell c;
    c.v = p.quad;
    c.nv = 4;
    out.cells.push_back(c);
    qsum += p.q;
  }
  int left = 0, left_wall = 0;
  for (int t = 0; t < nt; ++t)
    if (!used[t]) {
      out.cells.push_back(tri.cells[t]);
      ++left;
      left_wall += wall[t];
    }
  if (stats) {
    stats->triangles_in = nt;
    stats->quads = static_cast<int>(chosen.size());
    stats->triangles = left;
    stats->wall_triangles = left_wall;
    stats->mean_quality = chosen.empty() ? 0.0 : qsum / chosen.size();
    stats->candidate_pairs = static_cast<int>(pairs.size());
  }
  return out;
}

}  // namespace quadapt
