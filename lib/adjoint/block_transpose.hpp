#pragma once
// The transpose of a block-sparse DG matrix (lib/dg/block_matrix.hpp), block by block:
// (A^T)_{JI} = (A_{IJ})^T. The adjoint system A_h^T psi = g (thesis eq. 2.25) is solved with
// the same block solvers as the primal.
#include "dg/block_matrix.hpp"

namespace quadapt {

/// A^T with the same block size; block rows sorted by column as BlockSparseMatrix requires.
BlockSparseMatrix block_transpose(const BlockSparseMatrix& A);

}  // namespace quadapt
