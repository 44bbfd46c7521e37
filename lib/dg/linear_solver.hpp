#pragma once
// Sparse linear solvers for the DG system A U = b (and the adjoint's A^T psi = g).
//
// Kinds (names as given to dgsolve --solver):
//   umfpack        SuiteSparse UMFPACK sparse LU through Eigen (direct)
//   sparselu       Eigen's SparseLU with COLAMD (direct)
//   gmres-bilu0    restarted GMRES, right-preconditioned with block ILU(0) on the cell blocks
//   bicgstab-bilu0 BiCGSTAB with the same preconditioner
//   gmres-bjacobi  restarted GMRES with block Jacobi (cell blocks)
//   bicgstab-ilut  Eigen's BiCGSTAB with IncompleteLUT (scalar threshold ILU)
//   gmres-2level   restarted GMRES with the two-level preconditioner of dg/two_level.hpp (block
//                  ILU(0) smoother + continuous Q_q coarse space, q = min(p, 2) by default;
//                  needs opt.coarse)
//   auto           the measured default (docs/bench-dgsolve.md): gmres-2level when the problem
//                  has diffusion and a coarse space is given, else gmres-bilu0 (with the block
//                  order, e.g. downwind for advection); if that does not converge within
//                  auto_max_iterations (or its rate after a GMRES restart cycle projects more),
//                  the other iterative method, then umfpack.
// Iterative methods stop at ||b - A x|| <= rtol ||b|| (true residual checked at the end), or when
// the true residual is at the rounding level of A x in every row: |r_i| <= 1000 eps (|A| |x| + |b|)_i
// (componentwise backward error; stretched meshes with steep data have such a floor near 1e-12).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "dg/block_matrix.hpp"
#include "dg/discretization.hpp"
#include "dg/two_level.hpp"

namespace quadapt {

enum class LinearSolverKind {
  Auto, UmfPack, SparseLU, GmresBlockILU, BicgstabBlockILU, GmresBlockJacobi, BicgstabILUT, GmresTwoLevel
};

struct LinearSolverOptions {
  LinearSolverKind kind = LinearSolverKind::Auto;
  int block_size = 1;        ///< dense block size of the block preconditioners ((p+1)^2 for DG)
  double rtol = 1e-14;       ///< relative residual tolerance of the iterative methods (a residual at
                             ///< the rounding level of A x is accepted too)
  int max_iterations = 3000; ///< total Krylov iterations
  int restart = 80;          ///< GMRES restart length
  const CoarseSpace* coarse = nullptr;  ///< coarse space of gmres-2level (make_coarse_space)
  int coarse_degree = 0;     ///< degree q of the coarse space the callers build (0 = auto: min(p, 2))
  bool post_smooth = true;   ///< gmres-2level: smooth after the coarse correction too
  std::vector<int> block_order;  ///< elimination order of the block ILU (empty = natural)
  bool pure_advection = false;   ///< auto: no diffusion (the coarse space would not help)
  int auto_max_iterations = 300; ///< auto: iterations before trying the next method
};

struct LinearSolveInfo {
  std::string solver;             ///< name of the method that produced the solution
  int iterations = 0;             ///< Krylov iterations (0 for direct solvers)
  double relative_residual = 0;   ///< ||b - A x|| / ||b||
  double setup_seconds = 0;       ///< factorisation / preconditioner set-up
  double solve_seconds = 0;       ///< solve phase
  bool fallback = false;          ///< auto fell back to the direct solver
  int coarse_degree = 0;          ///< q of gmres-2level's coarse space when it was used, else 0
};

/// Whether a caller should build the coarse space (make_coarse_space) for these options: when
/// gmres-2level is asked for, or auto may choose it (the problem has diffusion). The one rule of
/// dgsolve and the adjoint: an explicit gmres-2level runs on pure advection too.
inline bool needs_coarse_space(LinearSolverKind kind, bool pure_advection) {
  return kind == LinearSolverKind::GmresTwoLevel || (kind == LinearSolverKind::Auto && !pure_advection);
}

/// When `info` is a fall-back to the direct solver: one sentence saying so, for a tool's
/// "warning: " line (the adaptive loop keeps those in its table's `warnings`); else "". A
/// fall-back costs the iterations spent first, so a system that falls back is solved faster by
/// the direct solver alone.
std::string fallback_note(const LinearSolveInfo& info);

/// Name <-> kind ("umfpack", ...). parse throws InputError listing the valid names.
LinearSolverKind parse_linear_solver(const std::string& name);
std::string linear_solver_name(LinearSolverKind kind);

/// Solves A x = b. Throws NumericalError when a direct factorisation fails or an explicitly
/// requested iterative method does not converge.
Eigen::VectorXd solve_linear(const SparseMatrixCSC& A, const Eigen::VectorXd& b, const LinearSolverOptions& opt,
                             LinearSolveInfo* info = nullptr);
/// Same for a block matrix (block size = opt.block_size is ignored; B's is used). Direct
/// solvers and bicgstab-ilut convert it to compressed columns first.
Eigen::VectorXd solve_linear(const BlockSparseMatrix& B, const Eigen::VectorXd& b, const LinearSolverOptions& opt,
                             LinearSolveInfo* info = nullptr);
/// The factor 2^k that brings the largest absolute matrix entry `max_abs` into [2^-64, 2^64],
/// or 1 when it is there already (or is 0 or not finite). Scaling A x = b by a power of two is
/// exact in floating point, so a system already in range solves to the same bytes; one far out
/// of it (a case with D = 1e100 I or 1e-100 I) would otherwise overflow or underflow the block
/// ILU's single-precision factors ("singular pivot block") although its solution is that of
/// D = I.
double system_scale(double max_abs);
/// Scales A (or B) and b by system_scale of A's largest entry; returns the factor (1: unchanged).
double scale_system(SparseMatrixCSC& A, Eigen::VectorXd& b);
double scale_system(BlockSparseMatrix& B, Eigen::VectorXd& b);
/// Whether `kind` works on compressed columns (direct solvers, bicgstab-ilut) rather than blocks.
bool uses_compressed_columns(LinearSolverKind kind);

}  // namespace quadapt
