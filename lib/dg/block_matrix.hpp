#pragma once
// Block-sparse matrices with dense square blocks (one block per pair of face-neighbour cells in
// a DG matrix), their OpenMP product with a vector, and the block ILU(0) preconditioner.
//
// Storage: block CSR. Block row I holds the blocks (I, J) for J in cols[row_start[I] ..
// row_start[I+1]), sorted; each block is nb x nb, column-major, at values + k * nb * nb.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "dg/huge_pages.hpp"

namespace quadapt {

class BlockSparseMatrix {
 public:
  BlockSparseMatrix() = default;
  /// Converts a compressed-column sparse matrix whose size is a multiple of nb. Entries missing
  /// from a block that has some entry are stored as zeros.
  BlockSparseMatrix(const Eigen::SparseMatrix<double, Eigen::ColMajor, int>& A, int nb);
  /// Zero matrix with the given block pattern (row_start: block_rows + 1 offsets into cols;
  /// cols sorted within each row).
  BlockSparseMatrix(int nb, std::vector<long long> row_start, std::vector<int> cols);

  int block_size() const { return nb_; }
  int block_rows() const { return nbr_; }
  int rows() const { return nbr_ * nb_; }
  long long num_blocks() const { return static_cast<long long>(cols_.size()); }

  /// The same matrix in compressed column storage (every block entry stored, zeros included).
  Eigen::SparseMatrix<double, Eigen::ColMajor, int> to_csc() const;

  /// y = A x (parallel over block rows, deterministic).
  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;
  /// y = |A| |x| (entrywise absolute values): the scale of the rounding error of A x.
  void multiply_abs(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;

  const std::vector<long long>& row_start() const { return row_start_; }
  const std::vector<int>& cols() const { return cols_; }
  const double* block(long long k) const { return values_.data() + k * nb_ * nb_; }
  double* block(long long k) { return values_.data() + k * nb_ * nb_; }
  /// All block values (num_blocks * nb * nb); release_values() frees them.
  const HugeVector<double>& values() const { return values_; }
  void release_values() { HugeVector<double>().swap(values_); }
  /// Multiplies every value by s (the pattern stays).
  void scale(double s) {
    for (long long k = 0; k < num_blocks() * nb_ * nb_; ++k) values_.data()[k] *= s;
  }
  /// Index k of block (I, J), or -1.
  long long find(int I, int J) const;

  /// The symmetrically permuted matrix B = P A P^T with block row/column order[i] of A becoming
  /// block i of B (`order` is a permutation of 0..block_rows()-1).
  BlockSparseMatrix permuted(const std::vector<int>& order) const;
  /// The block pattern of permuted(order) without its values: row_start (block_rows + 1), cols
  /// (sorted per row) and, per block of the permuted matrix, the index of A's block it holds.
  /// An empty `order` is the identity.
  void permuted_pattern(const std::vector<int>& order, std::vector<long long>& row_start, std::vector<int>& cols,
                        std::vector<long long>& source) const;

 private:
  int nb_ = 0, nbr_ = 0;
  std::vector<long long> row_start_;
  std::vector<int> cols_;
  HugeVector<double> values_;
};

/// Block incomplete LU with zero fill (ILU(0) on the block pattern, dense blocks) in the
/// matrix's block order: A ~ L U, L unit block-lower, U block-upper. apply() solves L U z = r.
/// The factorisation is sequential; its quality depends on the cell order (a downwind or
/// row-by-row order is best for advection). By default the factors are stored and applied in
/// single precision: the triangular solves are memory bound, and a preconditioner needs no more
/// accuracy (use it with flexible GMRES or BiCGSTAB, which tolerate an inexact preconditioner).
/// Each block row is eliminated in double precision in a small scratch buffer and written once
/// to the factor storage, so the set-up touches only the factor's memory (half of A's in single
/// precision) — no full-size double copy of A, whose first-touch page faults dominated the
/// set-up on our VMs (docs/adjoint.md).
class BlockILU0 {
 public:
  BlockILU0() = default;
  explicit BlockILU0(const BlockSparseMatrix& A) { compute(A); }
  /// Factorises in the block order `order` (elimination order: order[0] first); empty = natural.
  void compute(const BlockSparseMatrix& A, const std::vector<int>& order = {}, bool single_precision = true);
  void apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) const;

 private:
  template <class T>
  void factor(const BlockSparseMatrix& A, const std::vector<long long>& src, HugeVector<T>& vals);

  int n_ = 0, nb_ = 0;
  std::vector<long long> rs_;           ///< factor's block pattern in elimination order (CSR)
  std::vector<int> cols_;
  std::vector<long long> diag_;         ///< index of the diagonal block per row
  HugeVector<float> single_;            ///< L below, U above the diagonal; diagonal = inv(U_II)
  HugeVector<double> double_;           ///< the same in double precision (single_precision = false)
  std::vector<int> order_;              ///< elimination order (empty = natural)
};

/// Block Jacobi: z = inv(A_II) r_I per block row.
class BlockJacobi {
 public:
  BlockJacobi() = default;
  explicit BlockJacobi(const BlockSparseMatrix& A) { compute(A); }
  void compute(const BlockSparseMatrix& A);
  void apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) const;

 private:
  int nb_ = 0;
  std::vector<double> inv_;
};

}  // namespace quadapt
