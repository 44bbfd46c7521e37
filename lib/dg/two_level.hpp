#pragma once
// Two-level preconditioner for the DG system: block ILU(0) on the cell blocks as smoother and
// a coarse-grid correction in a space of continuous functions on the mesh (Dobrev, Lazarov,
// Vassilevski, Zikatanov, Numer. Linear Algebra Appl. 13, 2006: a continuous coarse space has no
// jumps, so the large SIPG penalty does not spoil it; the smoother handles the jumps and the
// high-order modes).
//
// Coarse space: continuous Q_q on the mesh (q = the coarse degree, 1 <= q <= p), nodal at the
// degree-q Gauss-Lobatto points of each cell: the mesh nodes (hanging nodes included, so it is
// continuous except across 2:1 faces — harmless for a preconditioner: a version whose hanging
// values were tied to the big edge's degree-q trace, continuous there too, gave the same GMRES
// counts to the iteration, e.g. 44 / 25 with Q_1 / Q_2 for D = diag(1, 1e-3), p = 3, on a
// fixed-fraction mesh with 1,214 hanging faces, against 18 / 11 on a conforming grid: what those
// faces cost under anisotropic diffusion is not the coarse space's jumps), q - 1 points inside each
// edge (shared by the edge's two cells) and (q - 1)^2 inside each cell. Prolongation P: in cell K
// the DG nodal values are the degree-q interpolant of the cell's coarse values, P_K(a, k) =
// l^q_kx(x_i) l^q_ky(x_j) at DG node a = (i, j). Coarse matrix A_c = P^T A P (Galerkin),
// factorised by UMFPACK (one step of iterative refinement, not its default of up to two:
// two_level.cpp).
// Why q = min(p, 2) by default (measured, docs/bench-dgsolve.md "Stretched adapted meshes"): on
// the boundary-layer loops' cells (up to ~100:1) the smooth-across, high-degree-along-the-wall
// modes of a stack of thin cells have little energy; Q_1 does not contain them and the cell-block
// smoother cannot reach them, so GMRES needed 40-44 (p = 2) and 56-67 (p = 3) iterations; with
// Q_2 14-15 and 28-30, with Q_3 at p = 3 12-14, but Q_3's factorisation costs more than its
// iterations save at 116k DOFs.
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

/// Prolongation from a continuous Q_q space to degree-p DG nodal values on each cell.
struct CoarseSpace {
  int degree = 1;                        ///< q
  int num_coarse = 0;                    ///< coarse unknowns: the mesh nodes, then the edges' and cells'
                                         ///< inner points as the cells (in order) first meet them
  int nb = 0;                            ///< (p+1)^2 DG values per cell
  int m = 0;                             ///< (q+1)^2 coarse values per cell
  std::vector<int> dof;                  ///< #cells x m: cell c's coarse value k = kx + (q+1) ky
  Eigen::MatrixXd shape;                 ///< nb x m: P_K (the same for every cell)
};
/// The coarse degree used when `requested` is 0 (auto): min(p, 2); else min(requested, p).
int coarse_degree(int p, int requested);
/// Continuous Q_degree on the mesh's quads for DG degree p (1 <= degree <= p). Throws InputError
/// when a cell is not a quad. An edge's inner points are keyed by its two end nodes (two distinct
/// curved edges between the same two nodes would share them: a poorer preconditioner, not a
/// wrong solution).
CoarseSpace make_coarse_space(const Mesh& mesh, int p, int degree);
/// The Galerkin coarse matrix A_c = P^T A P (#coarse x #coarse, compressed columns) on the pattern
/// of its nonzero block products; a coarse value in no cell gets a 1 on the diagonal. The same
/// bits with any thread count. Throws NumericalError when the space does not match A's blocks.
Eigen::SparseMatrix<double> galerkin_coarse_matrix(const BlockSparseMatrix& A, const CoarseSpace& coarse);

class TwoLevelPreconditioner {
 public:
  TwoLevelPreconditioner();
  ~TwoLevelPreconditioner();
  /// A: the DG matrix in block form (block = cell). Throws NumericalError if A_c is singular.
  /// `order`: elimination order of the block ILU smoother (empty = natural).
  void compute(const BlockSparseMatrix& A, const CoarseSpace& coarse, bool post_smooth = true,
               const std::vector<int>& order = {});
  void apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace quadapt
