#pragma once
// Two-level preconditioner for the DG system: block ILU(0) on the cell blocks as smoother and
// a coarse-grid correction in the space of continuous bilinear functions on the mesh vertices
// (Dobrev, Lazarov, Vassilevski, Zikatanov, Numer. Linear Algebra Appl. 13, 2006: a continuous
// coarse space has no jumps, so the large SIPG penalty does not spoil it; the smoother handles
// the jumps and the high-order modes).
//
// Coarse space: one unknown per mesh node (hanging nodes included, so it is continuous except
// across 2:1 faces — harmless for a preconditioner). Prolongation P: in cell K the DG nodal
// values are the bilinear interpolant of the 4 vertex values, P_K(a, k) = N_k(xi_a, eta_a).
// Coarse matrix A_c = P^T A P (Galerkin), factorised by UMFPACK.
// One application (multiplicative):  z = S r;  z += P A_c^-1 P^T (r - A z);  z += S' (r - A z),
// S = the block ILU(0) solve eliminating the cells in the given order, S' = the block ILU(0)
// solve in the reversed order (a forward and a backward sweep, as a symmetric Gauss-Seidel
// smoother pairs them). With `post_smooth = false` the last step is skipped.
// Why the reversed post-smoother (measured, docs/dgsolve.md "Linear solvers"): with S in both
// places, GMRES needed 127-177 iterations on adapted stretched meshes, or did not converge (an
// oblique layer, D = 0.01 I, 25:1 cells: relative residual 1.3e-6 after 1000 iterations); with S'
// 16-63. On structured and jittered grids the counts are the same either way.
// compute(): the two factorisations are independent and each sequential, so with two or more
// OpenMP threads they run side by side (the same factors bit for bit as one after the other).
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <vector>

#include "dg/block_matrix.hpp"
#include "mesh/mesh.hpp"

namespace quadapt {

/// Prolongation from vertex values to degree-p DG nodal values on each cell.
struct VertexCoarseSpace {
  int num_coarse = 0;                    ///< number of mesh nodes
  int nb = 0;                            ///< (p+1)^2
  std::vector<std::array<int, 4>> vert;  ///< per cell: its 4 node indices
  Eigen::MatrixXd shape;                 ///< nb x 4: N_k at the GLL nodes (same for every cell)
};
VertexCoarseSpace make_vertex_coarse_space(const Mesh& mesh, int p);

class TwoLevelPreconditioner {
 public:
  TwoLevelPreconditioner();
  ~TwoLevelPreconditioner();
  /// A: the DG matrix in block form (block = cell). Throws NumericalError if A_c is singular.
  /// `order`: elimination order of the block ILU smoother (empty = natural).
  void compute(const BlockSparseMatrix& A, const VertexCoarseSpace& coarse, bool post_smooth = true,
               const std::vector<int>& order = {});
  void apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace quadapt
