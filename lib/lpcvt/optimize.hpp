#pragma once
// Minimisation of the L_p-CVT energy over the free sites (thesis Algorithm 1): L-BFGS with the
// Moré-Thuente line search (strong Wolfe conditions, cubic interpolation) of LBFGSpp. LBFGSpp
// 0.1.0's LBFGSSolver does not compile with Moré-Thuente, so its L-BFGS-B solver is used with
// infinite bounds, which is plain L-BFGS.
//
// Scaling: the solver sees z = (x - x0) / L (L = the mean point spacing asked for by the
// metric) and f = E / (E0 / n_free) (E0 the energy at the start), so its tolerances are
// dimensionless: `gtol` bounds the largest per-site gradient component in units of
// (mean site energy / spacing).
//
// Stops: gradient below gtol ("gradient", converged); relative energy change below `delta`
// over `past` iterations ("energy", converged); the iteration cap ("iteration cap", not
// converged); a line-search failure (LBFGSpp throws std::runtime_error / std::logic_error;
// caught): L-BFGS restarts with fresh memory from the last accepted iterate (up to 5 times);
// when it fails again without progress the last accepted iterate is kept, and it counts as
// converged only when the gradient is already within 100 gtol ("line search at rounding level").
#include <functional>
#include <string>
#include <vector>

#include "lpcvt/background.hpp"

namespace quadapt::lpcvt {

struct LbfgsOptions {
  int max_iterations = 500;  ///< per call
  double gtol = 1e-6;        ///< scaled gradient (inf-norm) tolerance
  double delta = 1e-10;      ///< relative energy decrease over `past` iterations
  int past = 5;
  int memory = 7;            ///< L-BFGS correction pairs
  double xtol = 1e-5;        ///< step-size tolerance (relative to the spacing), see above
};

/// One accepted L-BFGS iterate (iteration 0 = the starting point).
struct IterationRecord {
  int cycle = 0;
  int iteration = 0;
  double energy = 0;     ///< E_Lp
  double grad_norm = 0;  ///< Euclidean norm of dE/dx over the free sites
  double step = 0;       ///< Euclidean norm of the site displacement of this iteration
  int evaluations = 0;   ///< energy evaluations so far in this call
  int points = 0;        ///< number of sites
};

struct MinimizeResult {
  int iterations = 0;
  int evaluations = 0;
  double energy = 0;
  double grad_norm = 0;
  bool converged = false;
  int restarts = 0;  ///< L-BFGS restarts after line-search failures
  std::string stop;  ///< "gradient", "energy", "iteration cap", "line search: ...", "no free sites"
};

/// Minimises E over sites[nfixed..] (sites[0..nfixed) stay fixed). Appends every accepted
/// iterate to `history` (with `cycle`), and calls `on_iteration` for each (progress).
MinimizeResult minimize_energy(const Background& bg, std::vector<Vec2>& sites, int nfixed, double p,
                               const LbfgsOptions& opt, std::vector<IterationRecord>* history = nullptr,
                               int cycle = 0,
                               const std::function<void(const IterationRecord&)>& on_iteration = {});

}  // namespace quadapt::lpcvt
