#include "lpcvt/energy.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>

#include "lpcvt/delaunay.hpp"
#include "fem/quadrature.hpp"

namespace quadapt::lpcvt {

namespace {

inline double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

/// f = |F|^p and g = df/dF.
inline void power(double F, double p, double& f, double& g) {
  if (p == 6) {
    double F2 = F * F, F4 = F2 * F2;
    f = F4 * F2;
    g = 6 * F4 * F;
  } else if (p == 2) {
    f = F * F;
    g = 2 * F;
  } else if (p == 4) {
    double F2 = F * F;
    f = F2 * F2;
    g = 4 * F2 * F;
  } else {
    double a = std::abs(F);
    if (a == 0) {
      f = 0;
      g = 0;
      return;
    }
    double am = std::pow(a, p - 1);
    f = am * a;
    g = p * am * (F < 0 ? -1 : 1);
  }
}


struct Contribution {
  int site;
  Vec2 g;
};

/// Append-only list of contributions that keeps its storage between evaluations.
struct ContribBuf {
  std::vector<Contribution> v;
  size_t n = 0;
  void clear() { n = 0; }
  void push(int site, const Vec2& g) {
    if (n == v.size()) v.resize(2 * n + 64);
    v[n].site = site;
    v[n].g = g;
    ++n;
  }
};

/// The vertex lines' chain rule: adds the contributions of dE/dv_k (G) through every vertex
/// that depends on sites (intersection of the lines of edges k-1 and k). Contributions to the
/// piece's own site are added to `gi`; those to a neighbour are summed per edge (acc) and
/// pushed once per bisector edge.
void chain_vertices(const RvdPiece& pc, const Background& bg, const std::vector<Vec2>& x,
                    const std::vector<Vec2>& G, Vec2& gi, std::vector<Vec2>& acc, ContribBuf& out) {
  const int m = static_cast<int>(pc.v.size());
  const Vec2& xi = x[pc.site];
  const IntegrationCell& Q = bg.cell(pc.cell);
  const Mat2 Gq = bg.partition_metric(pc.cell);  // the identity for Euclidean cells
  acc.assign(m, Vec2::Zero());
  for (int k = 0; k < m; ++k) {
    const int km = k == 0 ? m - 1 : k - 1;
    const int la = pc.label[km], lb = pc.label[k];
    if (la < 0 && lb < 0) continue;
    if (G[k].x() == 0 && G[k].y() == 0) continue;
    const Vec2& c = pc.v[k];
    auto normal = [&](int lab) -> Vec2 {
      if (lab >= 0) return Gq * (x[lab] - xi);
      int e = -1 - lab;
      Vec2 t = Q.v[(e + 1) % Q.nv] - Q.v[e];
      return Vec2(t.y(), -t.x());
    };
    const Vec2 n0 = normal(la), n1 = normal(lb);
    const double det = n0.x() * n1.y() - n0.y() * n1.x();
    if (!(std::abs(det) > 1e-300)) continue;
    // lambda = -A^-T G with A = [n0; n1]
    const double lam0 = -(n1.y() * G[k].x() - n1.x() * G[k].y()) / det;
    const double lam1 = -(-n0.y() * G[k].x() + n0.x() * G[k].y()) / det;
    // bisector g = (x_j - x_i)^T G (c - (x_i + x_j) / 2): dg/dx_i = G (x_i - c), dg/dx_j = G (c - x_j)
    if (la >= 0) {
      gi += lam0 * (Gq * (xi - c));
      acc[km] += lam0 * (Gq * (c - x[la]));
    }
    if (lb >= 0) {
      gi += lam1 * (Gq * (xi - c));
      acc[k] += lam1 * (Gq * (c - x[lb]));
    }
  }
  for (int k = 0; k < m; ++k)
    if (pc.label[k] >= 0 && (acc[k].x() != 0 || acc[k].y() != 0)) out.push(pc.label[k], acc[k]);
}

/// Quadrature path (analytic metrics, any p): returns the piece's energy, appends gradient
/// contributions when `out` != null.
double integrate_piece_rule(const RvdPiece& pc, const Background& bg, const std::vector<Vec2>& x,
                            double p, double gamma, const TriangleRule& rule, ContribBuf* out,
                            std::vector<Vec2>& G, std::vector<Vec2>& acc) {
  const int m = static_cast<int>(pc.v.size());
  const Vec2& xi = x[pc.site];
  const bool analytic = bg.is_analytic();
  Mat2 M = bg.cell(pc.cell).M, d0 = Mat2::Zero(), d1 = Mat2::Zero();
  double E = 0;
  Vec2 gx = Vec2::Zero();
  if (out) G.assign(m, Vec2::Zero());
  const Vec2& A = pc.v[0];
  for (int t = 1; t + 1 < m; ++t) {
    const Vec2 &B = pc.v[t], &C = pc.v[t + 1];
    const double J = cross(B - A, C - A);
    if (J == 0 && !out) continue;
    double Et = 0;
    Vec2 gxt = Vec2::Zero(), GA = Vec2::Zero(), GB = Vec2::Zero(), GC = Vec2::Zero();
    for (int q = 0; q < rule.size(); ++q) {
      const auto& l = rule.bary[q];
      const Vec2 y = l[0] * A + l[1] * B + l[2] * C;
      if (analytic) bg.metric_derivs(pc.cell, y, M, d0, d1);
      const Vec2 d = y - xi;
      const Vec2 F = M * d;
      double f0, g0, f1, g1;
      power(F.x(), p, f0, g0);
      power(F.y(), p, f1, g1);
      // weight omega = |det M(y)|^gamma (1 when gamma = 0)
      double omega = 1;
      if (gamma != 0) omega = std::pow(std::abs(M.determinant()), gamma);
      const double w = rule.w[q] * omega;
      Et += w * (f0 + f1);
      if (!out) continue;
      const Vec2 g(g0, g1);
      Vec2 gy = M.transpose() * g;  // d f / d y through (y - x)
      gxt -= w * gy;
      if (analytic) gy += Vec2(g.dot(d0 * d), g.dot(d1 * d));
      if (analytic && gamma != 0) {  // d omega / dy = gamma omega tr(M^-1 dM/dy)
        const Mat2 Mi = M.inverse();
        gy += (gamma * (f0 + f1)) * Vec2((Mi * d0).trace(), (Mi * d1).trace());
      }
      GA += (w * l[0]) * gy;
      GB += (w * l[1]) * gy;
      GC += (w * l[2]) * gy;
    }
    const double area = 0.5 * J;
    E += area * Et;
    if (!out) continue;
    gx += area * gxt;
    // d area / d vertex
    const Vec2 dJB(C.y() - A.y(), -(C.x() - A.x()));
    const Vec2 dJC(-(B.y() - A.y()), B.x() - A.x());
    G[0] += area * GA - 0.5 * Et * (dJB + dJC);
    G[t] += area * GB + 0.5 * Et * dJB;
    G[t + 1] += area * GC + 0.5 * Et * dJC;
  }
  if (!out) return E;
  chain_vertices(pc, bg, x, G, gx, acc, *out);
  out->push(pc.site, gx);
  return E;
}

/// h[n] = h_n(a, b, c), n = 0..P (complete homogeneous symmetric polynomials).
template <int P>
inline void complete_homogeneous(double a, double b, double c, double* h) {
  double ha = 1, hab = 1;
  h[0] = 1;
  for (int n = 1; n <= P; ++n) {
    ha *= a;
    hab = ha + b * hab;
    h[n] = hab + c * h[n - 1];
  }
}

/// d h_P / dz for z in (a, b, c): h_{P-1}(a, b, c, z) = sum_k z^k h_{P-1-k}(a, b, c).
template <int P>
inline double dh(const double* h, double z) {
  double s = h[0];
  for (int n = 1; n < P; ++n) s = s * z + h[n];
  return s;
}

/// Closed-form path (constant metric on the piece, even integer P): see energy.hpp.
template <int P>
double integrate_piece_closed(const RvdPiece& pc, const Background& bg, const std::vector<Vec2>& x,
                              double gamma, ContribBuf* out, std::vector<Vec2>& G, std::vector<Vec2>& F,
                              std::vector<Vec2>& acc) {
  const int m = static_cast<int>(pc.v.size());
  const Vec2& xi = x[pc.site];
  const Mat2& M = bg.cell(pc.cell).M;
  constexpr double kappa = 2.0 / ((P + 1.0) * (P + 2.0));
  F.resize(m);
  for (int k = 0; k < m; ++k) F[k] = M * (pc.v[k] - xi);
  if (out) G.assign(2 * m, Vec2::Zero());  // G[k]: dE/dF at vertex k; G[m + k]: geometric part
  double E = 0;
  double ha[P + 1], hb[P + 1];
  const Vec2& A = pc.v[0];
  for (int t = 1; t + 1 < m; ++t) {
    const Vec2 &B = pc.v[t], &C = pc.v[t + 1];
    const double J = cross(B - A, C - A);
    if (J == 0 && !out) continue;
    const Vec2 &a = F[0], &b = F[t], &c = F[t + 1];
    complete_homogeneous<P>(a.x(), b.x(), c.x(), ha);
    complete_homogeneous<P>(a.y(), b.y(), c.y(), hb);
    const double Et = kappa * (ha[P] + hb[P]);  // mean of the integrand over the facet
    const double area = 0.5 * J;
    E += area * Et;
    if (!out) continue;
    const double s = area * kappa;
    G[0] += s * Vec2(dh<P>(ha, a.x()), dh<P>(hb, a.y()));
    G[t] += s * Vec2(dh<P>(ha, b.x()), dh<P>(hb, b.y()));
    G[t + 1] += s * Vec2(dh<P>(ha, c.x()), dh<P>(hb, c.y()));
    const Vec2 dJB(C.y() - A.y(), -(C.x() - A.x()));
    const Vec2 dJC(-(B.y() - A.y()), B.x() - A.x());
    G[m] -= 0.5 * Et * (dJB + dJC);
    G[m + t] += 0.5 * Et * dJB;
    G[m + t + 1] += 0.5 * Et * dJC;
  }
  // constant weight (pow(x, 1) is x: the default gamma = 1 skips the call)
  const double adet = std::abs(M.determinant());
  const double omega = gamma == 0 ? 1.0 : gamma == 1 ? adet : std::pow(adet, gamma);
  if (!out) return omega * E;
  Vec2 sumF = Vec2::Zero();
  for (int k = 0; k < m; ++k) {
    sumF += G[k];
    G[k] = omega * (M.transpose() * G[k] + G[m + k]);  // dE/dv_k
  }
  Vec2 gi = -omega * (M.transpose() * sumF);
  G.resize(m);
  chain_vertices(pc, bg, x, G, gi, acc, *out);
  out->push(pc.site, gi);
  return omega * E;
}

using ClosedFn = double (*)(const RvdPiece&, const Background&, const std::vector<Vec2>&, double, ContribBuf*,
                            std::vector<Vec2>&, std::vector<Vec2>&, std::vector<Vec2>&);

ClosedFn closed_for(int p) {
  switch (p) {
    case 2: return &integrate_piece_closed<2>;
    case 4: return &integrate_piece_closed<4>;
    case 6: return &integrate_piece_closed<6>;
    case 8: return &integrate_piece_closed<8>;
    case 10: return &integrate_piece_closed<10>;
    case 12: return &integrate_piece_closed<12>;
    default: return nullptr;
  }
}

}  // namespace

struct EnergyWorkspace::Impl {
  std::unique_ptr<DelaunayGraph> dt;  // kept between evaluations (DelaunayGraph::update)
  std::unique_ptr<MetricGraph> mg;    // metric cells: dt flipped in the metric
  long updates = 0, rebuilds = 0, carried = 0;
  std::vector<int> starts;  // metric cells: the last evaluation's start sites (RestrictedVoronoi)
  std::unique_ptr<SiteTree> tree;  // metric cells, carried graph: the last evaluation's site tree
  int tree_age = 0;                // refits since it was built
  long tree_refits = 0;
  std::vector<ContribBuf> contrib;  // per integration cell
  struct Thread {
    RvdWorkspace rvd;
    std::vector<RvdPiece> pieces;
    std::vector<Vec2> G, F, acc;
  };
  std::vector<Thread> threads;
};
EnergyWorkspace::EnergyWorkspace() : impl(std::make_unique<Impl>()) {}
EnergyWorkspace::EnergyWorkspace(const EnergySettings& s) : settings(s), impl(std::make_unique<Impl>()) {}

EnergyTimers& EnergyTimers::operator+=(const EnergyTimers& o) {
  delaunay += o.delaunay;
  integrate += o.integrate;
  evaluations += o.evaluations;
  updates += o.updates;
  rebuilds += o.rebuilds;
  carried += o.carried;
  tree_refits += o.tree_refits;
  grid_searches += o.grid_searches;
  box_queries += o.box_queries;
  box_hits += o.box_hits;
  ellipse_queries += o.ellipse_queries;
  return *this;
}
EnergyWorkspace::~EnergyWorkspace() = default;

EnergyResult lp_energy(const RestrictedVoronoi& rvd, const Background& bg, double p,
                       bool gradient, EnergyWorkspace* ws, double gamma) {
  EnergyWorkspace local;
  EnergyWorkspace::Impl& W = ws ? *ws->impl : *local.impl;
  const EnergySettings& set = ws ? ws->settings : local.settings;
  const std::vector<Vec2>& x = rvd.sites();
  const int nq = bg.num_cells();
  const TriangleRule& rule = rule_for_exponent(p);
  const int ip = static_cast<int>(std::lround(p));
  const ClosedFn closed = set.closed_form && !bg.is_analytic() && ip == p ? closed_for(ip) : nullptr;
  std::vector<double> eq(nq, 0.0);
  if (gradient) {
    W.contrib.resize(nq);
    for (auto& c : W.contrib) c.clear();
  }
  std::vector<long> npieces(nq, 0);
  // Parallel only when there is enough work: small problems lose more to thread start-up and
  // (on a loaded machine) to spinning threads than they gain.
  const bool parallel = static_cast<int>(x.size()) >= std::max(0, set.min_parallel_sites) && nq >= 8;
  const int nthreads = parallel ? std::max(1, omp_get_max_threads()) : 1;
  if (static_cast<int>(W.threads.size()) < nthreads) W.threads.resize(nthreads);
#pragma omp parallel num_threads(nthreads) if (parallel)
  {
    EnergyWorkspace::Impl::Thread& T = W.threads[omp_get_thread_num()];
#pragma omp for schedule(dynamic, 8)
    for (int q = 0; q < nq; ++q) {
      const int n = rvd.pieces(q, T.pieces, T.rvd);
      npieces[q] = n;
      double e = 0;
      ContribBuf* out = gradient ? &W.contrib[q] : nullptr;
      for (int k = 0; k < n; ++k)
        e += closed ? closed(T.pieces[k], bg, x, gamma, out, T.G, T.F, T.acc)
                    : integrate_piece_rule(T.pieces[k], bg, x, p, gamma, rule, out, T.G, T.acc);
      eq[q] = e;
    }
  }
  EnergyResult r;
  for (int q = 0; q < nq; ++q) {
    r.energy += eq[q];
    r.pieces += npieces[q];
  }
  if (gradient) {
    r.grad.assign(x.size(), Vec2::Zero());
    for (int q = 0; q < nq; ++q)
      for (size_t k = 0; k < W.contrib[q].n; ++k) r.grad[W.contrib[q].v[k].site] += W.contrib[q].v[k].g;
  }
  return r;
}

EnergyResult lp_energy(const Background& bg, const std::vector<Vec2>& sites, double p,
                       bool gradient, EnergyWorkspace* ws, double gamma) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  std::unique_ptr<RestrictedVoronoi> rvd;
  if (ws) {
    EnergyWorkspace::Impl& W = *ws->impl;
    const bool metric = bg.metric_cells();
    // metric cells: the last evaluation's metric graph carried to the new sites by flips (no
    // Euclidean Delaunay graph), else (too many triangles would invert, or have been carried
    // inverted since the last rebuild) rebuilt from the Euclidean one
    const double frac = ws->settings.carry_inverted;
    const long nt = W.mg ? static_cast<long>(W.mg->tris.size()) : 0;
    const bool carry = metric && ws->settings.carry_metric_graph && W.mg &&
                       W.starts.size() == static_cast<size_t>(bg.num_cells()) && W.mg->inverted <= 10 * frac * nt &&
                       update_metric_graph(bg, sites, *W.mg, static_cast<int>(frac * nt));
    if (carry) {
      ++W.carried;
    } else if (!W.dt) {
      W.dt = std::make_unique<DelaunayGraph>(sites, metric, !metric);
      ++W.rebuilds;
    } else if (W.dt->update(sites)) {
      ++W.updates;
    } else {
      ++W.rebuilds;
    }
    if (carry) {
      // the site tree of the evaluation before, refitted to the moved sites (O(n) instead of
      // O(n log n)); built anew every tree_refits + 1 evaluations so its halves stay apart
      if (W.tree && W.tree->size() == static_cast<int>(sites.size()) && W.tree_age < ws->settings.tree_refits) {
        W.tree->refit(sites);
        ++W.tree_age;
        ++W.tree_refits;
      } else {
        W.tree = std::make_unique<SiteTree>(sites);
        W.tree_age = 0;
      }
      rvd = std::make_unique<RestrictedVoronoi>(bg, sites, *W.mg, W.starts, W.tree.get());
    } else if (metric) {
      W.tree.reset();
      W.mg = std::make_unique<MetricGraph>(build_metric_graph(bg, sites, *W.dt));
      rvd = std::make_unique<RestrictedVoronoi>(bg, sites, *W.dt, W.mg.get());
    } else {
      rvd = std::make_unique<RestrictedVoronoi>(bg, sites, *W.dt);
    }
  } else {
    rvd = std::make_unique<RestrictedVoronoi>(bg, sites);
  }
  if (ws && bg.metric_cells()) {
    ws->impl->starts = rvd->starts();
    rvd->set_grid_min_sites(ws->settings.grid_min_sites);
  }
  const auto t1 = Clock::now();
  EnergyResult r = lp_energy(*rvd, bg, p, gradient, ws, gamma);
  const auto t2 = Clock::now();
  if (ws) {
    EnergyTimers& T = ws->timers;
    T.delaunay += std::chrono::duration<double>(t1 - t0).count();
    T.updates = ws->impl->updates;
    T.rebuilds = ws->impl->rebuilds;
    T.carried = ws->impl->carried;
    T.tree_refits = ws->impl->tree_refits;
    T.box_queries = T.box_hits = T.grid_searches = T.ellipse_queries = 0;
    for (const auto& th : ws->impl->threads) {
      T.grid_searches += th.rvd.grid_searches;
      T.box_queries += th.rvd.box_queries;
      T.box_hits += th.rvd.box_hits;
      T.ellipse_queries += th.rvd.ellipse_queries;
    }
    T.integrate += std::chrono::duration<double>(t2 - t1).count();
    ++T.evaluations;
  }
  return r;
}

std::vector<std::pair<int, int>> last_graph_edges(const EnergyWorkspace& ws) {
  std::vector<std::pair<int, int>> e;
  const EnergyWorkspace::Impl& W = *ws.impl;
  auto collect = [&](const auto& g) {
    for (int i = 0; i < g.num_sites(); ++i)
      for (const int* j = g.nbr_begin(i); j != g.nbr_end(i); ++j)
        if (i < *j) e.emplace_back(i, *j);
  };
  if (W.mg)
    collect(*W.mg);
  else if (W.dt)
    collect(*W.dt);
  return e;
}

double piece_energy(const RvdPiece& piece, const Background& bg, const Vec2& x_site, double p) {
  std::vector<Vec2> x(static_cast<size_t>(piece.site) + 1, x_site);
  std::vector<Vec2> G, acc;
  return integrate_piece_rule(piece, bg, x, p, 0.0, rule_for_exponent(p), nullptr, G, acc);
}

}  // namespace quadapt::lpcvt
