#include "adjoint/block_transpose.hpp"

#include <Eigen/Core>
#include <utility>
#include <vector>

namespace quadapt {

BlockSparseMatrix block_transpose(const BlockSparseMatrix& A) {
  const int n = A.block_rows(), nb = A.block_size();
  const std::vector<long long>& rs = A.row_start();
  const std::vector<int>& cols = A.cols();
  // Block (I, J) of A becomes block (J, I): count the blocks of every column J of A.
  std::vector<long long> start(n + 1, 0);
  for (long long k = 0; k < A.num_blocks(); ++k) ++start[cols[k] + 1];
  for (int J = 0; J < n; ++J) start[J + 1] += start[J];
  std::vector<int> tcols(static_cast<size_t>(A.num_blocks()));
  std::vector<long long> src(static_cast<size_t>(A.num_blocks()));
  std::vector<long long> next(start.begin(), start.end() - 1);
  for (int I = 0; I < n; ++I)  // increasing I keeps every row of the transpose sorted
    for (long long k = rs[I]; k < rs[I + 1]; ++k) {
      const long long at = next[cols[k]]++;
      tcols[at] = I;
      src[at] = k;
    }
  BlockSparseMatrix T(nb, start, std::move(tcols));
#pragma omp parallel for schedule(static)
  for (long long k = 0; k < T.num_blocks(); ++k)
    Eigen::Map<Eigen::MatrixXd>(T.block(k), nb, nb) = Eigen::Map<const Eigen::MatrixXd>(A.block(src[k]), nb, nb).transpose();
  return T;
}

bool transpose_in_place(BlockSparseMatrix& A) {
  const int n = A.block_rows(), nb = A.block_size();
  const std::vector<long long>& rs = A.row_start();
  const std::vector<int>& cols = A.cols();
  std::vector<long long> mirror(static_cast<size_t>(A.num_blocks()));
  for (int I = 0; I < n; ++I)
    for (long long k = rs[I]; k < rs[I + 1]; ++k) {
      mirror[k] = A.find(cols[k], I);
      if (mirror[k] < 0) return false;
    }
  using Map = Eigen::Map<Eigen::MatrixXd>;
#pragma omp parallel for schedule(static)
  for (int I = 0; I < n; ++I)
    for (long long k = rs[I]; k < rs[I + 1]; ++k) {
      const int J = cols[k];
      if (J < I) continue;
      Map a(A.block(k), nb, nb);
      if (J == I) {
        a.transposeInPlace();
      } else {
        Map b(A.block(mirror[k]), nb, nb);
        for (int j = 0; j < nb; ++j)
          for (int i = 0; i < nb; ++i) std::swap(a(i, j), b(j, i));
      }
    }
  return true;
}

}  // namespace quadapt
