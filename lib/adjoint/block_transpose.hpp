#pragma once
// The transpose of a block-sparse DG matrix (lib/dg/block_matrix.hpp), block by block:
// (A^T)_{JI} = (A_{IJ})^T. The adjoint system A_h^T psi = g (thesis eq. 2.25) is solved with
// the same block solvers as the primal.
#include "dg/block_matrix.hpp"

namespace quadapt {

/// A^T with the same block size; block rows sorted by column as BlockSparseMatrix requires.
BlockSparseMatrix block_transpose(const BlockSparseMatrix& A);

/// Replaces A by A^T in its own storage when its block pattern is structurally symmetric (as
/// every DG matrix's face-neighbour pattern is): blocks (I, J) and (J, I) are swapped and
/// transposed. No allocation — a fresh 100 MB buffer costs more in first-touch page faults than
/// the copy itself. Returns false, leaving A unchanged, when the pattern is not symmetric.
bool transpose_in_place(BlockSparseMatrix& A);

}  // namespace quadapt
