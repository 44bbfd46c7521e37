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
//   auto           the measured default (docs/bench-dgsolve.md): umfpack.
// Iterative methods stop at ||b - A x|| <= rtol ||b|| (true residual checked at the end).
#include <Eigen/Core>
#include <string>

#include "dg/discretization.hpp"

namespace quadapt {

enum class LinearSolverKind { Auto, UmfPack, SparseLU, GmresBlockILU, BicgstabBlockILU, GmresBlockJacobi, BicgstabILUT };

struct LinearSolverOptions {
  LinearSolverKind kind = LinearSolverKind::Auto;
  int block_size = 1;        ///< dense block size of the block preconditioners ((p+1)^2 for DG)
  double rtol = 1e-12;       ///< relative residual tolerance of the iterative methods
  int max_iterations = 3000; ///< total Krylov iterations
  int restart = 80;          ///< GMRES restart length
};

struct LinearSolveInfo {
  std::string solver;             ///< name of the method that produced the solution
  int iterations = 0;             ///< Krylov iterations (0 for direct solvers)
  double relative_residual = 0;   ///< ||b - A x|| / ||b||
  double setup_seconds = 0;       ///< factorisation / preconditioner set-up
  double solve_seconds = 0;       ///< solve phase
  bool fallback = false;          ///< auto fell back to the direct solver
};

/// Name <-> kind ("umfpack", ...). parse throws InputError listing the valid names.
LinearSolverKind parse_linear_solver(const std::string& name);
std::string linear_solver_name(LinearSolverKind kind);

/// Solves A x = b. Throws NumericalError when a direct factorisation fails or an explicitly
/// requested iterative method does not converge.
Eigen::VectorXd solve_linear(const SparseMatrixCSC& A, const Eigen::VectorXd& b, const LinearSolverOptions& opt,
                             LinearSolveInfo* info = nullptr);

}  // namespace quadapt
