#pragma once
// Exact solve of the adjoint system A^T psi = g by one block sweep, when A^T is block lower
// triangular in a given cell order: the case of pure advection with the upwind flux and cells
// ordered downstream first (thesis eq. 2.25 for D = 0). The adjoint of the upwind scheme
// transports information against the flow, so cell I only couples to the cells downstream of
// it; visiting the cells downstream first, each step is one dense (p+2)^2 solve with the cell's
// diagonal block. Cost: one block LU per cell, no Krylov iterations, no ILU set-up.
#include <Eigen/Core>
#include <vector>

#include "dg/block_matrix.hpp"

namespace quadapt {

/// Solves A^T x = g by the block sweep in the cell order `order` (order[k] = the cell solved
/// k-th), reading A's blocks directly (no transposed copy). Returns false, leaving x
/// unspecified, when A's block pattern is not structurally symmetric, A^T is not block lower
/// triangular in that order (a non-zero block A(J, I) with J after I), or a diagonal block is
/// singular. Deterministic (sequential). `relative_residual` (optional) receives
/// ||g - A^T x|| / ||g|| (rounding level for a successful sweep).
bool solve_transposed_block_sweep(const BlockSparseMatrix& A, const std::vector<int>& order, const Eigen::VectorXd& g,
                                  Eigen::VectorXd& x, double* relative_residual = nullptr);

}  // namespace quadapt
