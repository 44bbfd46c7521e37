#pragma once
// The dual-weighted residual (DWR) error estimate of a boundary functional on the enriched
// degree-(p+1) DG space (thesis sections 2.3-2.4, eqs. 2.18-2.27, section 5.4; docs/design.md §4).
//
// Given the degree-p solution u_H of dgsolve on a mesh (conforming or 2:1 non-conforming):
//   1. inject u_H into the degree-(p+1) space on the same mesh: u_h^H = I_h^H u_H (exact, the
//      polynomial is unchanged; DGDiscretization::inject);
//   2. the fine residual R_h(u_h^H) = A_h u_h^H - b_h and the fine Jacobian dR_h/du_h = A_h
//      (the problem is linear, so A_h does not depend on the linearisation point);
//   3. the fine adjoint (eq. 2.25):  A_h^T psi = (dJ/du_h |_{u_h^H})^T, J(u) = int_Gamma u^2 ds
//      over the case's functional boundary, i.e. g_a = int_Gamma 2 u_h^H phi_a ds;
//   4. the signed estimate (eq. 2.26)  J(u) - J_H(u_H) ~ -psi^T R_h(u_h^H), and per cell
//      eta_k = | sum_{a in cell k} psi_a R_a |  (eq. 2.27).
//
// Linearisation point: the gradient of J is taken at the injected coarse solution u_h^H (thesis
// eq. 2.25): it is the only state available without a fine primal solve. For this linear PDE
// the estimate then equals, to rounding,
//     -psi^T R = J(u_h) - J(u_h^H) - int_Gamma (u_h - u_h^H)^2 ds,
// with u_h the fine (p+1) DG solution; the missing quadratic term is O(h^(2p+2)), one order
// beyond the functional error itself, so the effectivity tends to 1 as the mesh is refined.
//
// psi holds the nodal (GLL) values of the discrete adjoint function z_h = sum_a psi_a phi_a,
// which satisfies a_h(v, z_h) = J'(u_h^H)[v] for every fine v: a viewable degree-(p+1) field.
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "case/case.hpp"
#include "dg/block_matrix.hpp"
#include "dg/discretization.hpp"
#include "dg/linear_solver.hpp"
#include "mesh/mesh.hpp"

namespace quadapt {

/// Cell order of the adjoint solve (the block sweep's visiting order, the block ILU(0)'s
/// elimination order).
///   Flow:  downstream first: the adjoint of an upwind scheme carries information against the
///          flow. Pure advection: upwind_order of -c (lib/dg/solve.hpp), a topological order
///          of the reversed flow, in which the transposed operator is block lower triangular —
///          one exact block sweep; with diffusion downwind_order of -c (centroids). When c = 0:
///          dgsolve's sweep in y (the same order as the primal's).
///   Mesh:  the mesh's cell order.
///   Auto:  Flow (the default). The mesh order was auto's choice with diffusion until measured
///          on adapted meshes, whose file order is arbitrary: gmres-2level needed 46-229
///          iterations there against 16-22 in the flow order (S-shock goal loop, p = 2), and an
///          advection-dominated case fell back to UMFPACK (docs/adjoint.md, Solver).
enum class AdjointOrdering { Auto, Mesh, Flow };

struct AdjointOptions {
  DGOptions dg;                  ///< must match the primal solve's (penalty factor, quadrature)
  /// The adjoint linear solver (lib/dg/linear_solver.hpp); block_size, block_order, the coarse
  /// space and pure_advection are filled in. Default auto: one block sweep for pure advection
  /// (adjoint/block_sweep.hpp), else gmres-2level, then gmres-bilu0, then UMFPACK when they do
  /// not converge (measured, docs/adjoint.md). Default rtol 1e-10: the estimate's error is
  /// r^T (u_h - u_h^H) for the adjoint residual r, i.e. at most rtol ||g|| ||u_h - u_h^H||.
  LinearSolverOptions solver = default_solver();
  AdjointOrdering ordering = AdjointOrdering::Auto;
  /// An explicitly chosen iterative solver that does not reach its tolerance: solve again with
  /// UMFPACK (LinearSolveInfo::fallback) instead of throwing.
  bool fallback_direct = true;

  static LinearSolverOptions default_solver() {
    LinearSolverOptions o;
    o.rtol = 1e-10;
    return o;
  }
};

struct DWRResult {
  int p = 0;                     ///< degree of the primal solution
  int p_fine = 0;                ///< p + 1
  long long dofs = 0;            ///< coarse DOFs  #cells (p+1)^2
  long long fine_dofs = 0;       ///< fine DOFs    #cells (p+2)^2
  Eigen::VectorXd psi;           ///< fine adjoint (fine_dofs)
  Eigen::VectorXd residual;      ///< R_h(u_h^H) (fine_dofs)
  std::vector<double> eta;       ///< per cell |psi_k^T R_k|  (eq. 2.27)
  std::vector<double> eta_signed;///< per cell -psi_k^T R_k (sums to the estimate)
  double functional = 0;         ///< J_H(u_H) = J(u_h^H)
  double functional_exact = 0;   ///< J(u) from the case's exact solution
  double functional_error = 0;   ///< J(u) - J_H(u_H)
  double estimate = 0;           ///< -psi^T R_h(u_h^H), estimate of functional_error (eq. 2.26)
  double sum_eta = 0;            ///< sum_k eta_k >= |estimate| (eq. 2.27)
  double effectivity = 0;        ///< estimate / functional_error (NaN when the error is 0)
  double corrected = 0;          ///< adjoint-corrected functional J_H(u_H) + estimate
  LinearSolveInfo solve;         ///< adjoint linear solve (method, iterations, residual)
  std::vector<std::pair<std::string, double>> timings;  ///< wall seconds per phase, in order
};

/// The report figures of r (docs/adjoint.md): p, p_fine, dofs, fine_dofs, functional*,
/// sum_eta, effectivity (null when not finite), eta_max, residual_norm, solver_*.
nlohmann::json to_json(const DWRResult& r);

/// `mesh` with the cell field "dwr" (eta) and the degree-(p+1) DG field "psi" of r added.
void add_dwr_fields(Mesh& mesh, const DWRResult& r);

/// The discretisation options of the fine (degree p + 1) space for a primal solved with
/// `primal` at degree p: the same, with the primal's SIPG penalty sigma = factor p(p+1) n^T D n
/// / h_F on interior faces (factor scaled by p / (p + 2)), so that the fine form restricted to
/// the primal's space V_H is the primal's form there. Then R_h(u_H)(v_H) = 0 for every v_H in
/// V_H supported on one cell off the Dirichlet faces (Galerkin orthogonality, up to the finer
/// quadrature), which the cell indicators
/// eta_k = |psi_k^T R_k| rely on: with the fine space's own penalty (p+1)(p+2) the penalty
/// mismatch gave each cell a term (sigma_fine - sigma_H) [u_H] . psi that cancels between
/// neighbours — sum_k eta_k up to 1e5 x |estimate| where the adjoint is O(1) (a functional on a
/// natural boundary) and goal-oriented loops 3-20x worse than uniform refinement
/// (docs/adjoint.md, "Cell indicators"). No effect without diffusion (sigma ~ n^T D n).
/// Dirichlet faces keep the fine space's own penalty (a heuristic: the weak boundary mismatch
/// stays in the indicators in the proportion (p+2)/p). Keep penalty_factor >= 5: the fine
/// interior factor is lower.
DGOptions fine_dg_options(const DGOptions& primal, int p);

/// Computes the DWR estimate for the degree-p DG vector U (#cells (p+1)^2) on `mesh` for case
/// `cs`. Throws InputError when the case has no functional or names a boundary the mesh lacks,
/// or when U has the wrong size; NumericalError when the adjoint solve fails.
DWRResult compute_dwr(const Mesh& mesh, const Case& cs, const Eigen::VectorXd& U, int p,
                      const AdjointOptions& opt = {});

/// Solves the adjoint system A^T psi = g for the fine DG matrix A (blocks = cells of `mesh`,
/// degree pf) with opt.solver, the Flow/Mesh elimination order for advection c and, for
/// gmres-2level, the mesh's continuous Q_q coarse space (q = opt.solver.coarse_degree, 0 = min(pf, 2)). Falls back to UMFPACK as
/// opt.fallback_direct says; throws NumericalError otherwise.
/// A is taken by value (pass it with std::move to release it once it has been transposed).
/// `topo`: the mesh's faces, if the caller has them (for the pure-advection order).
Eigen::VectorXd solve_adjoint(BlockSparseMatrix A, const Eigen::VectorXd& g, const Mesh& mesh, int pf,
                              const Eigen::Vector2d& c, bool pure_advection, const AdjointOptions& opt,
                              LinearSolveInfo* info = nullptr, const Topology* topo = nullptr);

/// The degree-p DG solution stored in `mesh` as the CellNodeField `field` (dgsolve's "u"), as a
/// coefficient vector (#cells (p+1)^2). Throws InputError("PATH: ...") when the field is missing
/// (naming the fields present), is not a scalar tensor-GLL DG field of degree >= 1, does not cover
/// every cell, or holds a non-finite value.
Eigen::VectorXd read_solution_field(const Mesh& mesh, const std::string& field, const std::string& path, int& p);

}  // namespace quadapt
