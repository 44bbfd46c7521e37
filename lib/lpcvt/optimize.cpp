#include "lpcvt/optimize.hpp"

#include <LBFGSpp/LineSearchMoreThuente.h>
#include <LBFGSpp/Param.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <stdexcept>
#include <vector>

#include "lpcvt/block_ops.hpp"
#include "lpcvt/energy.hpp"

namespace quadapt::lpcvt {

namespace {
using VecX = Eigen::VectorXd;
using Index = Eigen::Index;

using namespace blocks;
}  // namespace

double edge_change_rms(const std::vector<std::pair<int, int>>& edges, const std::vector<Mat2>& M,
                       const std::vector<Vec2>& d) {
  const Index ne = static_cast<Index>(edges.size());
  if (ne == 0) return 0.0;
  const double s = block_sum(ne, [&](Index b, Index e) {
    double t = 0;
    for (Index k = b; k < e; ++k) {
      const auto [i, j] = edges[k];
      const Vec2 dd = d[j] - d[i];
      t += 0.5 * ((M[i] * dd).squaredNorm() + (M[j] * dd).squaredNorm());
    }
    return t;
  });
  return std::sqrt(s / ne);
}

MinimizeResult minimize_energy(const Background& bg, std::vector<Vec2>& sites, int nfixed, double p,
                               const LbfgsOptions& opt, std::vector<IterationRecord>* history,
                               int cycle, const std::function<void(const IterationRecord&)>& on_iteration) {
  MinimizeResult res;
  const int n = static_cast<int>(sites.size());
  const int nfree = n - nfixed;
  if (nfree <= 0) {
    EnergyResult e = lp_energy(bg, sites, p, false, nullptr, opt.gamma);
    res.energy = e.energy;
    res.converged = true;
    res.stop = "no free sites";
    return res;
  }
  const double L = bg.mean_spacing();
  const std::vector<Vec2> x0 = sites;
  std::vector<Vec2> work = sites;
  double escale = 1;
  int evals = 0;

  // Variables z: x_i = x0_i + P_i z_i with P_i = L I, or with opt.precondition the local frame
  // P_i = L sqrt|det M_i| M_i^-1 (M_i at the start position): the per-site Hessian of the energy
  // is about (cell area) M^T M, so in z it is about isotropic and the same for every site.
  std::vector<Mat2> P(nfree, L * Mat2::Identity());
  if (opt.precondition) {
    int hint = -1;
    for (int i = 0; i < nfree; ++i) {
      const int c = bg.locate(x0[nfixed + i], hint);
      if (c < 0) continue;
      hint = c;
      const Mat2 M = bg.metric(c, x0[nfixed + i]);
      P[i] = L * std::sqrt(std::abs(M.determinant())) * M.inverse();
    }
  }
  // Metric of every free site at its start position, times P: |MP_i dz_i| is the site's
  // displacement in units of the local point spacing (M_eff has unit spacing).
  // Ms: every site's metric at its start position (fixed sites too: the edge measure of "mesh
  // settled" below).
  std::vector<Mat2> Ms(n), MP(nfree);
  auto metrics_at_start = [&](int b, int e) {
    int hint = -1;
    for (int i = b; i < e; ++i) {
      int c = bg.locate(x0[i], hint);
      if (c < 0) c = hint >= 0 ? hint : 0;
      hint = c;
      Ms[i] = bg.metric(c, x0[i]);
    }
  };
  metrics_at_start(nfixed, n);
  metrics_at_start(0, nfixed);
  for (int i = 0; i < nfree; ++i) MP[i] = Ms[nfixed + i] * P[i];
  auto metric_rms = [&](const VecX& dz) {
    const double s = block_sum(nfree, [&](Index b, Index e) {
      double t = 0;
      for (Index i = b; i < e; ++i) t += (MP[i] * Vec2(dz[2 * i], dz[2 * i + 1])).squaredNorm();
      return t;
    });
    return std::sqrt(s / nfree);
  };
  EnergyWorkspace ews(opt.energy);
  auto f = [&](const VecX& z, VecX& gz) -> double {
    for_blocks(nfree, [&](Index b, Index e) {
      for (Index i = b; i < e; ++i) work[nfixed + i] = x0[nfixed + i] + P[i] * Vec2(z[2 * i], z[2 * i + 1]);
    });
    EnergyResult e = lp_energy(bg, work, p, true, &ews, opt.gamma);
    ++evals;
    gz.resize(2 * nfree);
    for_blocks(nfree, [&](Index b, Index en) {
      for (Index i = b; i < en; ++i) {
        const Vec2 gi = P[i].transpose() * e.grad[nfixed + i] / escale;
        gz[2 * i] = gi.x();
        gz[2 * i + 1] = gi.y();
      }
    });
    return e.energy / escale;
  };
  auto unscaled_gnorm = [&](const VecX& gz) {
    const double s = block_sum(nfree, [&](Index b, Index e) {
      double t = 0;
      for (Index i = b; i < e; ++i) t += (P[i].transpose().inverse() * Vec2(gz[2 * i], gz[2 * i + 1])).squaredNorm();
      return t;
    });
    return std::sqrt(s) * escale;
  };
  auto displacement = [&](const VecX& dz) {
    const double s = block_sum(nfree, [&](Index b, Index e) {
      double t = 0;
      for (Index i = b; i < e; ++i) t += (P[i] * Vec2(dz[2 * i], dz[2 * i + 1])).squaredNorm();
      return t;
    });
    return std::sqrt(s);
  };

  // Starting point and energy scale.
  VecX z = VecX::Zero(2 * nfree), g;
  const double e0 = f(z, g);
  // "mesh settled": the start's neighbour graph (edges with a free end)
  std::vector<std::pair<int, int>> gedges;
  std::vector<Vec2> dwin;  // a window's move, all sites (fixed: zero)
  if (opt.past > 0) {
    for (const auto& e : last_graph_edges(ews))
      if (e.second >= nfixed) gedges.push_back(e);
    dwin.assign(n, Vec2::Zero());
  }
  auto window_edges = [&](const VecX& dz) {
    for_blocks(nfree, [&](Index b, Index e) {
      for (Index i = b; i < e; ++i) dwin[nfixed + i] = P[i] * Vec2(dz[2 * i], dz[2 * i + 1]);
    });
    return edge_change_rms(gedges, Ms, dwin);
  };
  escale = (e0 > 0 && std::isfinite(e0)) ? e0 / nfree : 1.0;
  g /= escale;  // re-express in the new scale (f was computed with escale = 1)
  double fx = e0 / escale;
  int iter = 0;
  VecX zsnap = z;                // sites at the last window check (every opt.past iterations)
  bool window_checked = false;   // a window has just closed: test move_tol
  std::vector<std::pair<double, double>> recent;  // (energy, step) of the accepted iterates
  auto record = [&](double fxx, const VecX& gz, double step) {
    IterationRecord r;
    r.cycle = cycle;
    r.iteration = iter;
    r.energy = fxx * escale;
    r.grad_norm = unscaled_gnorm(gz);
    r.step = step;
    r.evaluations = evals;
    r.points = n;
    if (history) history->push_back(r);
    recent.emplace_back(r.energy, r.step);
    if (on_iteration) on_iteration(r);
    res.energy = r.energy;
    res.grad_norm = r.grad_norm;
  };
  record(fx, g, 0.0);  // iteration 0

  LBFGSpp::LBFGSBParam<double> param;
  param.max_linesearch = 40;
  const int m = std::max(1, opt.memory);
  std::deque<VecX> S, Y;
  std::deque<double> rho;
  VecX d, xp, gp, q;
  std::vector<double> alpha(m);
  int restarts = 0;
  bool fresh = true;  // first step after a (re)start
  int since_restart = 0;
  auto stagnated = [&](int past, double tol) {
    if (static_cast<int>(recent.size()) <= past) return false;
    const size_t k = recent.size() - 1;
    const double de = (recent[k - past].first - recent[k].first) / std::max(std::abs(recent[k].first), 1e-300);
    return de <= tol;
  };
  for (;;) {
    if (g.lpNorm<Eigen::Infinity>() <= opt.gtol) {
      res.stop = "gradient";
      res.converged = true;
      break;
    }
    if (window_checked && opt.move_tol > 0 && res.window_move <= opt.move_tol) {
      res.stop = "points settled";
      res.converged = true;
      break;
    }
    if (window_checked && opt.edge_tol > 0 && res.window_edge_change <= opt.edge_tol) {
      res.stop = "mesh settled";
      res.converged = true;
      break;
    }
    window_checked = false;
    if (since_restart >= opt.past && stagnated(opt.past, opt.delta)) {
      res.stop = "energy";
      res.converged = true;
      break;
    }
    if (opt.max_iterations > 0 && iter >= opt.max_iterations) {
      res.stop = "iteration cap";
      res.converged = false;
      break;
    }
    // Two-loop recursion: d = -H g, H0 = (s.y / y.y) I.
    q = g;
    const int h = static_cast<int>(S.size());
    for (int k = h - 1; k >= 0; --k) {
      alpha[k] = rho[k] * dot(S[k], q);
      axpy(-alpha[k], Y[k], q);
    }
    if (h > 0) {
      const double c = dot(S[h - 1], Y[h - 1]) / sqnorm(Y[h - 1]);
      for_blocks(q.size(), [&](Index b, Index e) { q.segment(b, e - b) *= c; });
    }
    for (int k = 0; k < h; ++k) {
      const double beta = rho[k] * dot(Y[k], q);
      axpy(alpha[k] - beta, S[k], q);
    }
    d = -q;
    // first step after a (re)start: a move of about 1/10 of the spacing for the largest site
    double step = fresh ? std::min(1.0, 0.1 / std::max(d.lpNorm<Eigen::Infinity>(), 1e-300)) : 1.0;
    xp = z;
    gp = g;
    const double fp = fx;
    try {
      if (g.dot(d) >= 0) throw std::logic_error("not a descent direction");
      LBFGSpp::LineSearchMoreThuente<double>::LineSearch(f, fx, z, g, step, param.max_step, d, xp, param);
    } catch (const std::exception& e) {
      // Typically where the energy is not smooth (a Voronoi vertex crossing a metric jump) or at
      // rounding level: restart with fresh memory from the last accepted iterate.
      z = xp;
      g = gp;
      fx = fp;
      const bool tiny = g.lpNorm<Eigen::Infinity>() <= 100 * opt.gtol;
      // stagnant over the last five accepted iterates, or all of them when fewer (a lattice start
      // that is already the optimum: the same energy to the last digit from the first iterate)
      const int span = std::min(5, static_cast<int>(recent.size()) - 1);
      if (tiny || (span >= 2 && stagnated(span, 1e-9))) {
        res.stop = tiny ? "line search at rounding level" : "line search, energy stagnant";
        res.converged = true;
        break;
      }
      if (fresh || restarts >= 5) {
        res.stop = std::string("line search: ") + e.what();
        res.converged = false;
        break;
      }
      ++restarts;
      res.restarts = restarts;
      S.clear();
      Y.clear();
      rho.clear();
      fresh = true;
      since_restart = 0;
      continue;
    }
    ++iter;
    ++since_restart;
    fresh = false;
    VecX s = z - xp, y = g - gp;
    const double sy = dot(s, y);
    record(fx, g, displacement(s));
    if (opt.past > 0 && iter % opt.past == 0) {
      res.window_move = metric_rms(z - zsnap);
      res.window_edge_change = window_edges(z - zsnap);
      zsnap = z;
      if (history) {
        history->back().window_move = res.window_move;
        history->back().window_edge_change = res.window_edge_change;
      }
      window_checked = true;
    }
    if (sy > 1e-12 * sqnorm(y)) {
      if (static_cast<int>(S.size()) == m) {
        S.pop_front();
        Y.pop_front();
        rho.pop_front();
      }
      S.push_back(std::move(s));
      Y.push_back(std::move(y));
      rho.push_back(1.0 / sy);
    }
  }
  for (int i = 0; i < nfree; ++i) sites[nfixed + i] = x0[nfixed + i] + P[i] * Vec2(z[2 * i], z[2 * i + 1]);
  res.iterations = iter;
  res.evaluations = evals;
  res.timers = ews.timers;
  return res;
}

}  // namespace quadapt::lpcvt
