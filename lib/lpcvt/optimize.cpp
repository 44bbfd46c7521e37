#include "lpcvt/optimize.hpp"

#include <LBFGSB.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "lpcvt/energy.hpp"

namespace quadapt::lpcvt {

namespace {

using VecX = Eigen::VectorXd;

/// Receives every accepted iterate from the line search below.
struct Recorder {
  std::function<void(double fx, const VecX& x, const VecX& xp, const VecX& grad)> accept;
};
thread_local Recorder* tl_recorder = nullptr;

/// Moré-Thuente, reporting each accepted step (LBFGSpp has no iteration callback).
template <class Scalar>
class RecordingMoreThuente {
 public:
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  template <typename Foo>
  static void LineSearch(Foo& f, Scalar& fx, Vector& x, Vector& grad, Scalar& step,
                         const Scalar& step_max, const Vector& drt, const Vector& xp,
                         const LBFGSpp::LBFGSBParam<Scalar>& param) {
    LBFGSpp::LineSearchMoreThuente<Scalar>::LineSearch(f, fx, x, grad, step, step_max, drt, xp, param);
    if (tl_recorder && tl_recorder->accept) tl_recorder->accept(fx, x, xp, grad);
  }
};

}  // namespace

MinimizeResult minimize_energy(const Background& bg, std::vector<Vec2>& sites, int nfixed, double p,
                               const LbfgsOptions& opt, std::vector<IterationRecord>* history,
                               int cycle, const std::function<void(const IterationRecord&)>& on_iteration) {
  MinimizeResult res;
  const int n = static_cast<int>(sites.size());
  const int nfree = n - nfixed;
  if (nfree <= 0) {
    EnergyResult e = lp_energy(bg, sites, p, false);
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

  // Variables z: x_i = x0_i + L z_i (P_i = L I). A per-site preconditioner by the local
  // metric shape (L sqrt|det M| M^-1) was tried and converged more slowly, to higher energies,
  // on a 4:1 frame at 45 degrees (1276 vs 723 iterations), so it is not used.
  std::vector<Mat2> P(nfree, L * Mat2::Identity());
  auto f = [&](const VecX& z, VecX& gz) -> double {
    for (int i = 0; i < nfree; ++i) work[nfixed + i] = x0[nfixed + i] + P[i] * Vec2(z[2 * i], z[2 * i + 1]);
    EnergyResult e = lp_energy(bg, work, p, true);
    ++evals;
    gz.resize(2 * nfree);
    for (int i = 0; i < nfree; ++i) {
      Vec2 g = P[i].transpose() * e.grad[nfixed + i] / escale;
      gz[2 * i] = g.x();
      gz[2 * i + 1] = g.y();
    }
    return e.energy / escale;
  };
  auto displacement = [&](const VecX& dz) {
    double s = 0;
    for (int i = 0; i < nfree; ++i) s += (P[i] * Vec2(dz[2 * i], dz[2 * i + 1])).squaredNorm();
    return std::sqrt(s);
  };
  std::vector<Mat2> PinvT(nfree);
  for (int i = 0; i < nfree; ++i) PinvT[i] = P[i].inverse().transpose();
  auto unscaled_gnorm = [&](const VecX& gz) {  // |dE/dx| from the scaled gradient
    double s = 0;
    for (int i = 0; i < nfree; ++i) s += (PinvT[i] * Vec2(gz[2 * i], gz[2 * i + 1])).squaredNorm();
    return std::sqrt(s) * escale;
  };

  // Starting point and energy scale.
  VecX z = VecX::Zero(2 * nfree), g0;
  escale = 1;
  const double e0 = f(z, g0);
  escale = (e0 > 0 && std::isfinite(e0)) ? e0 / nfree : 1.0;
  g0 *= 1.0 / escale;  // re-express in the new scale (f was computed with escale = 1)
  VecX best = z;
  double last_ginf = g0.lpNorm<Eigen::Infinity>();
  int iter = 0;
  std::vector<std::pair<double, double>> recent;  // (energy, step) of the accepted iterates
  auto record = [&](double fx, const VecX& zz, const VecX& zp, const VecX& gz) {
    IterationRecord r;
    r.cycle = cycle;
    r.iteration = iter;
    r.energy = fx * escale;
    r.grad_norm = unscaled_gnorm(gz);
    r.step = displacement(zz - zp);
    r.evaluations = evals;
    r.points = n;
    if (history) history->push_back(r);
    recent.emplace_back(r.energy, r.step);
    if (on_iteration) on_iteration(r);
    res.energy = r.energy;
    res.grad_norm = r.grad_norm;
    last_ginf = gz.lpNorm<Eigen::Infinity>();
  };
  record(e0 / escale, z, z, g0);  // iteration 0

  Recorder rec;
  rec.accept = [&](double fx, const VecX& zz, const VecX& zp, const VecX& gz) {
    ++iter;
    best = zz;
    record(fx, zz, zp, gz);
  };
  Recorder* saved = tl_recorder;
  tl_recorder = &rec;

  LBFGSpp::LBFGSBParam<double> param;
  param.m = opt.memory;
  param.epsilon = opt.gtol;
  param.epsilon_rel = 0;
  param.past = opt.past;
  param.delta = opt.delta;
  param.max_linesearch = 40;
  const double inf = std::numeric_limits<double>::infinity();
  VecX lb = VecX::Constant(2 * nfree, -inf), ub = VecX::Constant(2 * nfree, inf);
  double fx = 0;
  if (last_ginf <= opt.gtol) {
    res.stop = "gradient";
    res.converged = true;
  }
  // A line-search failure (typically where the energy is not smooth: a Voronoi vertex crossing
  // a metric jump) restarts L-BFGS, with fresh memory, from the last accepted iterate.
  for (int restarts = 0; !res.converged;) {
    const int iter_before = iter;
    param.max_iterations = std::max(1, opt.max_iterations - iter);
    LBFGSpp::LBFGSBSolver<double, RecordingMoreThuente> solver(param);
    z = best;
    try {
      solver.minimize(f, z, fx, lb, ub);
      best = z;  // the last accepted iterate (recorded)
      if (last_ginf <= opt.gtol) {
        res.stop = "gradient";
        res.converged = true;
      } else if (opt.max_iterations > 0 && iter >= opt.max_iterations) {
        res.stop = "iteration cap";
        res.converged = false;
      } else {
        res.stop = "energy";
        res.converged = true;
      }
      break;
    } catch (const std::exception& e) {
      // `best` is the last accepted iterate (its energy and gradient are recorded)
      if (last_ginf <= 100 * opt.gtol) {
        res.stop = "line search at rounding level";
        res.converged = true;
        break;
      }
      // Step-size test (thesis Algorithm 1: |dx| or |grad E| below a tolerance): the last
      // accepted steps are tiny and the energy no longer moves.
      if (recent.size() >= 6) {
        const size_t k = recent.size() - 1;
        const double de = std::abs(recent[k - 5].first - recent[k].first) / std::max(std::abs(recent[k].first), 1e-300);
        if (recent[k].second <= opt.xtol * L * std::sqrt(double(nfree)) && de <= 1e-9) {
          res.stop = "step size";
          res.converged = true;
          break;
        }
      }
      if (iter == iter_before || restarts >= 5 || iter >= opt.max_iterations) {
        res.stop = std::string("line search: ") + e.what();
        res.converged = false;
        break;
      }
      ++restarts;
      res.restarts = restarts;
    }
  }
  tl_recorder = saved;
  for (int i = 0; i < nfree; ++i) sites[nfixed + i] = x0[nfixed + i] + P[i] * Vec2(best[2 * i], best[2 * i + 1]);
  res.iterations = iter;
  res.evaluations = evals;
  return res;
}

}  // namespace quadapt::lpcvt
