#pragma once
// Minimisation of the L_p-CVT energy over the free sites (thesis Algorithm 1): L-BFGS (two-loop
// recursion, written here) with the Moré-Thuente line search (strong Wolfe conditions, cubic
// interpolation) of LBFGSpp. (LBFGSpp 0.1.0's LBFGSSolver does not compile with Moré-Thuente;
// its L-BFGS-B solver with infinite bounds, used before, spent ~10% of the time in its Cauchy
// point and subspace minimisation.)
//
// Scaling: the solver sees z = (x - x0) / L (L = the mean point spacing asked for by the
// metric) and f = E / (E0 / n_free) (E0 the energy at the start), so its tolerances are
// dimensionless: `gtol` bounds the largest per-site gradient component in units of
// (mean site energy / spacing).
//
// Stops: gradient below gtol ("gradient", converged); the points settled: every `past`
// iterations, the RMS over the free sites of |M(x_i) (x_i(k) - x_i(k - past))| (M = M_eff at
// the site's position at the start of the call, unit = the local point spacing) is at most
// `move_tol` ("points settled", converged); the mesh settled: every `past` iterations, the RMS
// change of the edge vectors of the start's neighbour graph in the metric (edge_change_rms, unit
// = the target edge) is at most `edge_tol` ("mesh settled", converged) — unlike the points' move
// it does not count a drift of the whole point set, which leaves every edge as it is (at 1.1e6
// points the RMS move stays at 0.07-0.09 of the spacing over 150 iterations while the edges'
// change falls from 0.06 to 0.03: docs/lpcvt.md *Convergence*); relative energy change below `delta` over `past`
// iterations ("energy", converged); the iteration cap ("iteration cap", not
// converged); a line-search failure (LBFGSpp throws; caught): L-BFGS restarts with fresh memory
// from the last accepted iterate (up to 5 times); when the first step after a restart fails
// too, the last accepted iterate is kept. A failure counts as converged when the gradient is
// within 100 gtol ("line search at rounding level") or the energy changed by less than 1e-9
// (relative) over the last 5 iterations ("line search, energy stagnant").
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "lpcvt/background.hpp"
#include "lpcvt/energy.hpp"

namespace quadapt::lpcvt {

struct LbfgsOptions {
  int max_iterations = 500;  ///< per call
  double gtol = 1e-6;        ///< scaled gradient (inf-norm) tolerance
  double delta = 1e-10;      ///< relative energy decrease over `past` iterations
  int past = 5;
  double move_tol = 0;       ///< "points settled": RMS metric displacement over `past` iterations (0 = off)
  double edge_tol = 0;       ///< "mesh settled": RMS metric change of the graph's edges over `past` iterations (0 = off)
  int memory = 7;            ///< L-BFGS correction pairs
  bool precondition = false; ///< variables scaled by the local frame (optimize.cpp)
  double gamma = 0;          ///< energy weight |det M|^gamma (energy.hpp); 0 = the thesis's energy
  EnergySettings energy;     ///< how the energy is evaluated (energy.hpp)
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
  double window_move = -1;  ///< RMS metric displacement over the last `past` iterations, on the
                            ///< iterations where that window closes (k = past, 2 past, ...); else -1
  double window_edge_change = -1;  ///< on the same iterations: edge_change_rms over the window; else -1
};

struct MinimizeResult {
  int iterations = 0;
  int evaluations = 0;
  double energy = 0;
  double grad_norm = 0;
  bool converged = false;
  int restarts = 0;  ///< L-BFGS restarts after line-search failures
  double window_move = -1;  ///< the last closed window's RMS metric displacement (-1: none)
  double window_edge_change = -1;  ///< the last closed window's edge_change_rms (-1: none)
  std::string stop;  ///< "gradient", "points settled", "mesh settled", "energy", "iteration cap", "line search: ...", "no free sites"
  EnergyTimers timers;  ///< time in the energy evaluations of this call
};

/// How much a move d (#sites, physical units) changes the edges {i, j} of a neighbour graph, in
/// the metric M (#sites, e.g. M_eff at each site; unit = the target edge):
///   sqrt( mean over the edges of ( |M_i (d_j - d_i)|^2 + |M_j (d_j - d_i)|^2 ) / 2 ).
/// Zero for a translation; depends on M^T M only (a reflected M gives the same). 0 without edges.
/// Sums in fixed blocks: the same value for any thread count.
double edge_change_rms(const std::vector<std::pair<int, int>>& edges, const std::vector<Mat2>& M,
                       const std::vector<Vec2>& d);

/// Minimises E over sites[nfixed..] (sites[0..nfixed) stay fixed). Appends every accepted
/// iterate to `history` (with `cycle`), and calls `on_iteration` for each (progress).
MinimizeResult minimize_energy(const Background& bg, std::vector<Vec2>& sites, int nfixed, double p,
                               const LbfgsOptions& opt, std::vector<IterationRecord>* history = nullptr,
                               int cycle = 0,
                               const std::function<void(const IterationRecord&)>& on_iteration = {});

}  // namespace quadapt::lpcvt
