#include "adjoint/block_sweep.hpp"

#include <Eigen/LU>
#include <cmath>

namespace quadapt {

bool solve_transposed_block_sweep(const BlockSparseMatrix& A, const std::vector<int>& order, const Eigen::VectorXd& g,
                                  Eigen::VectorXd& x, double* relative_residual) {
  const int n = A.block_rows(), nb = A.block_size();
  if (static_cast<int>(order.size()) != n || g.size() != A.rows()) return false;
  std::vector<int> pos(n, -1);
  for (int k = 0; k < n; ++k) {
    if (order[k] < 0 || order[k] >= n || pos[order[k]] >= 0) return false;
    pos[order[k]] = k;
  }
  const std::vector<long long>& rs = A.row_start();
  const std::vector<int>& cols = A.cols();
  // Row I of A^T holds the blocks A(J, I)^T for the J of row I's pattern (symmetric pattern).
  // transposed[k] = index of block (cols[k], I) for k in row I.
  std::vector<long long> transposed(static_cast<size_t>(A.num_blocks()));
  for (int I = 0; I < n; ++I)
    for (long long k = rs[I]; k < rs[I + 1]; ++k) {
      const int J = cols[k];
      const long long t = A.find(J, I);
      if (t < 0) return false;
      transposed[k] = t;
      if (pos[J] > pos[I]) {  // must vanish: A^T(I, J) with J solved later
        const double* blk = A.block(t);
        for (int e = 0; e < nb * nb; ++e)
          if (blk[e] != 0.0) return false;
      }
    }
  x.setZero(A.rows());
  Eigen::VectorXd r(nb);
  Eigen::PartialPivLU<Eigen::MatrixXd> lu;
  for (int k = 0; k < n; ++k) {
    const int I = order[k];
    r = g.segment(static_cast<Eigen::Index>(I) * nb, nb);
    long long diag = -1;
    for (long long q = rs[I]; q < rs[I + 1]; ++q) {
      const int J = cols[q];
      if (J == I) {
        diag = transposed[q];
        continue;
      }
      if (pos[J] < pos[I])
        r.noalias() -= Eigen::Map<const Eigen::MatrixXd>(A.block(transposed[q]), nb, nb).transpose() *
                       x.segment(static_cast<Eigen::Index>(J) * nb, nb);
    }
    if (diag < 0) return false;
    lu.compute(Eigen::Map<const Eigen::MatrixXd>(A.block(diag), nb, nb).transpose());
    if (!(std::abs(lu.determinant()) > 0)) return false;
    x.segment(static_cast<Eigen::Index>(I) * nb, nb) = lu.solve(r);
  }
  if (!x.allFinite()) return false;
  if (relative_residual) {
    double res2 = 0;
    for (int I = 0; I < n; ++I) {
      r = g.segment(static_cast<Eigen::Index>(I) * nb, nb);
      for (long long q = rs[I]; q < rs[I + 1]; ++q)
        r.noalias() -= Eigen::Map<const Eigen::MatrixXd>(A.block(transposed[q]), nb, nb).transpose() *
                       x.segment(static_cast<Eigen::Index>(cols[q]) * nb, nb);
      res2 += r.squaredNorm();
    }
    const double gn = g.norm();
    *relative_residual = gn > 0 ? std::sqrt(res2) / gn : 0.0;
  }
  return true;
}

}  // namespace quadapt
