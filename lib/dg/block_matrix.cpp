#include "dg/block_matrix.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <type_traits>
#include <stdexcept>

#include "core/error.hpp"
#include "dg/block_dispatch.hpp"

namespace quadapt {

namespace {
using MapM = Eigen::Map<Eigen::MatrixXd>;
using CMapM = Eigen::Map<const Eigen::MatrixXd>;

}  // namespace

BlockSparseMatrix::BlockSparseMatrix(const Eigen::SparseMatrix<double, Eigen::ColMajor, int>& A, int nb) {
  if (nb < 1 || A.rows() != A.cols() || A.rows() % nb != 0)
    throw NumericalError("block matrix: size " + std::to_string(A.rows()) + " is not a multiple of the block size " +
                         std::to_string(nb));
  if (!A.isCompressed()) throw NumericalError("block matrix: the sparse matrix must be compressed");
  nb_ = nb;
  nbr_ = static_cast<int>(A.rows() / nb);
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  const double* val = A.valuePtr();

  // Pattern: count the blocks of every block row, then list them (block columns ascend).
  std::vector<int> marker(nbr_, -1);
  std::vector<long long> count(nbr_ + 1, 0);
  for (int C = 0; C < nbr_; ++C)
    for (int j = C * nb; j < (C + 1) * nb; ++j)
      for (int p = outer[j]; p < outer[j + 1]; ++p) {
        int R = inner[p] / nb;
        if (marker[R] != C) {
          marker[R] = C;
          ++count[R + 1];
        }
      }
  row_start_.assign(nbr_ + 1, 0);
  for (int R = 0; R < nbr_; ++R) row_start_[R + 1] = row_start_[R] + count[R + 1];
  cols_.resize(row_start_[nbr_]);
  std::vector<long long> fill(row_start_.begin(), row_start_.end() - 1);
  std::fill(marker.begin(), marker.end(), -1);
  for (int C = 0; C < nbr_; ++C)
    for (int j = C * nb; j < (C + 1) * nb; ++j)
      for (int p = outer[j]; p < outer[j + 1]; ++p) {
        int R = inner[p] / nb;
        if (marker[R] != C) {
          marker[R] = C;
          cols_[fill[R]++] = C;
        }
      }
  values_.assign(static_cast<size_t>(cols_.size()) * nb * nb, 0.0);
  // Values: every block column writes only its own blocks.
#pragma omp parallel
  {
    std::vector<int> mk(nbr_, -1);
    std::vector<long long> kpos(nbr_, -1);
#pragma omp for schedule(static)
    for (int C = 0; C < nbr_; ++C)
      for (int j = C * nb; j < (C + 1) * nb; ++j)
        for (int p = outer[j]; p < outer[j + 1]; ++p) {
          int r = inner[p], R = r / nb;
          if (mk[R] != C) {
            mk[R] = C;
            kpos[R] = find(R, C);
          }
          values_[static_cast<size_t>(kpos[R]) * nb * nb + static_cast<size_t>(j - C * nb) * nb + (r - R * nb)] =
              val[p];
        }
  }
}

BlockSparseMatrix::BlockSparseMatrix(int nb, std::vector<long long> row_start, std::vector<int> cols)
    : nb_(nb), nbr_(static_cast<int>(row_start.size()) - 1), row_start_(std::move(row_start)), cols_(std::move(cols)) {
  values_.assign(cols_.size() * static_cast<size_t>(nb) * nb, 0.0);
}

Eigen::SparseMatrix<double, Eigen::ColMajor, int> BlockSparseMatrix::to_csc() const {
  // Blocks of every block column, in increasing block row.
  std::vector<long long> cstart(nbr_ + 1, 0);
  for (int c : cols_) ++cstart[c + 1];
  for (int C = 0; C < nbr_; ++C) cstart[C + 1] += cstart[C];
  std::vector<std::pair<int, long long>> bycol(cols_.size());
  std::vector<long long> fill(cstart.begin(), cstart.end() - 1);
  for (int R = 0; R < nbr_; ++R)
    for (long long k = row_start_[R]; k < row_start_[R + 1]; ++k) bycol[fill[cols_[k]]++] = {R, k};
  const long long nnz = static_cast<long long>(cols_.size()) * nb_ * nb_;
  if (nnz > 2000000000LL) throw NumericalError("block matrix too large for 32-bit sparse indices");
  Eigen::SparseMatrix<double, Eigen::ColMajor, int> A(rows(), rows());
  A.resizeNonZeros(static_cast<Eigen::Index>(nnz));
  int* outer = A.outerIndexPtr();
  int* inner = A.innerIndexPtr();
  double* val = A.valuePtr();
  outer[rows()] = static_cast<int>(nnz);
#pragma omp parallel for schedule(static)
  for (int C = 0; C < nbr_; ++C) {
    const long long nblk = cstart[C + 1] - cstart[C];
    for (int j = 0; j < nb_; ++j) {
      long long base = cstart[C] * nb_ * nb_ + static_cast<long long>(j) * nblk * nb_;
      outer[C * nb_ + j] = static_cast<int>(base);
      for (long long t = 0; t < nblk; ++t) {
        const auto [R, k] = bycol[cstart[C] + t];
        const double* src = block(k) + static_cast<long long>(j) * nb_;
        for (int a = 0; a < nb_; ++a) {
          inner[base + t * nb_ + a] = R * nb_ + a;
          val[base + t * nb_ + a] = src[a];
        }
      }
    }
  }
  return A;
}

long long BlockSparseMatrix::find(int I, int J) const {
  auto b = cols_.begin() + row_start_[I], e = cols_.begin() + row_start_[I + 1];
  auto it = std::lower_bound(b, e, J);
  return (it != e && *it == J) ? static_cast<long long>(it - cols_.begin()) : -1;
}

void BlockSparseMatrix::permuted_pattern(const std::vector<int>& order, std::vector<long long>& row_start,
                                         std::vector<int>& cols, std::vector<long long>& source) const {
  if (!order.empty() && static_cast<int>(order.size()) != nbr_)
    throw NumericalError("block matrix: permutation of the wrong size");
  auto old_row = [&](int i) { return order.empty() ? i : order[i]; };
  std::vector<int> inv(nbr_, -1);
  for (int i = 0; i < nbr_; ++i) {
    const int I = old_row(i);
    if (I < 0 || I >= nbr_ || inv[I] >= 0) throw NumericalError("block matrix: not a permutation");
    inv[I] = i;
  }
  row_start.assign(nbr_ + 1, 0);
  for (int i = 0; i < nbr_; ++i) row_start[i + 1] = row_start[i] + (row_start_[old_row(i) + 1] - row_start_[old_row(i)]);
  cols.resize(cols_.size());
  source.resize(cols_.size());
#pragma omp parallel
  {
    std::vector<std::pair<int, long long>> row;
#pragma omp for schedule(static)
    for (int i = 0; i < nbr_; ++i) {
      const int I = old_row(i);
      row.clear();
      for (long long k = row_start_[I]; k < row_start_[I + 1]; ++k) row.emplace_back(inv[cols_[k]], k);
      std::sort(row.begin(), row.end());
      long long out = row_start[i];
      for (const auto& [j, k] : row) {
        cols[out] = j;
        source[out++] = k;
      }
    }
  }
}

BlockSparseMatrix BlockSparseMatrix::permuted(const std::vector<int>& order) const {
  if (static_cast<int>(order.size()) != nbr_) throw NumericalError("block matrix: permutation of the wrong size");
  BlockSparseMatrix B;
  B.nb_ = nb_;
  B.nbr_ = nbr_;
  std::vector<long long> source;
  permuted_pattern(order, B.row_start_, B.cols_, source);
  B.values_.resize(values_.size());
  const long long bs = static_cast<long long>(nb_) * nb_;
#pragma omp parallel for schedule(static)
  for (long long e = 0; e < static_cast<long long>(source.size()); ++e)
    std::copy(values_.begin() + source[e] * bs, values_.begin() + (source[e] + 1) * bs, B.values_.begin() + e * bs);
  return B;
}

void BlockSparseMatrix::multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  y.resize(rows());
  const int nb = nb_;
  dispatch_block_size(nb, [&](auto NBc) {
    constexpr int NB = decltype(NBc)::value;
    using Mat = Eigen::Matrix<double, NB, NB>;
    using Vec = Eigen::Matrix<double, NB, 1>;
#pragma omp parallel for schedule(static)
    for (int I = 0; I < nbr_; ++I) {
      Vec acc = Vec::Zero(nb);
      for (long long k = row_start_[I]; k < row_start_[I + 1]; ++k)
        acc.noalias() += Eigen::Map<const Mat>(block(k), nb, nb) *
                         Eigen::Map<const Vec>(x.data() + static_cast<Eigen::Index>(cols_[k]) * nb, nb);
      Eigen::Map<Vec>(y.data() + static_cast<Eigen::Index>(I) * nb, nb) = acc;
    }
  });
}

void BlockSparseMatrix::multiply_abs(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  y.resize(rows());
  const int nb = nb_;
#pragma omp parallel for schedule(static)
  for (int I = 0; I < nbr_; ++I) {
    Eigen::VectorXd acc = Eigen::VectorXd::Zero(nb);
    for (long long k = row_start_[I]; k < row_start_[I + 1]; ++k)
      acc.noalias() += CMapM(block(k), nb, nb).cwiseAbs() * x.segment(static_cast<Eigen::Index>(cols_[k]) * nb, nb).cwiseAbs();
    y.segment(static_cast<Eigen::Index>(I) * nb, nb) = acc;
  }
}

// ---------------------------------------------------------------------------- block ILU(0)

void BlockILU0::compute(const BlockSparseMatrix& A, const std::vector<int>& order, bool single_precision) {
  n_ = A.block_rows();
  nb_ = A.block_size();
  order_ = order;
  std::vector<long long> src;  // src[e] = A's block behind factor block e
  A.permuted_pattern(order, rs_, cols_, src);
  diag_.assign(n_, -1);
  for (int i = 0; i < n_; ++i) {
    auto b = cols_.begin() + rs_[i], e = cols_.begin() + rs_[i + 1];
    auto it = std::lower_bound(b, e, i);
    if (it == e || *it != i) throw NumericalError("block ILU: block row " + std::to_string(i) + " has no diagonal block");
    diag_[i] = it - cols_.begin();
  }
  HugeVector<float>().swap(single_);
  HugeVector<double>().swap(double_);
  if (single_precision)
    factor(A, src, single_);
  else
    factor(A, src, double_);
}

template <class T>
void BlockILU0::factor(const BlockSparseMatrix& A, const std::vector<long long>& src, HugeVector<T>& vals) {
  const int nb = nb_;
  const size_t bs = static_cast<size_t>(nb) * nb;
  vals.resize(cols_.size() * bs);  // written once, row by row below
  dispatch_block_size(nb, [&](auto NBc) {
    constexpr int NB = decltype(NBc)::value;
    using Mat = Eigen::Matrix<double, NB, NB>;
    using MatT = Eigen::Matrix<T, NB, NB>;
    auto stored = [&](long long k) { return Eigen::Map<const MatT>(vals.data() + k * bs, nb, nb).template cast<double>(); };
    std::vector<double> work;  // block row i in double precision
    Mat tmp(nb, nb), U(nb, nb);
    for (int i = 0; i < n_; ++i) {
      const long long r0 = rs_[i], r1 = rs_[i + 1];
      work.resize(static_cast<size_t>(r1 - r0) * bs);
      auto wblk = [&](long long k) { return Eigen::Map<Mat>(work.data() + (k - r0) * bs, nb, nb); };
      for (long long k = r0; k < r1; ++k) std::copy_n(A.block(src[k]), bs, work.data() + (k - r0) * bs);
      for (long long k = r0; k < diag_[i]; ++k) {
        const int K = cols_[k];
        auto LIK = wblk(k);
        U = stored(diag_[K]);  // inv(U_KK)
        tmp.noalias() = LIK.lazyProduct(U);
        LIK = tmp;
        // Row i -= L_iK * (row K beyond its diagonal), restricted to row i's pattern.
        long long a = k + 1;
        for (long long b = diag_[K] + 1; b < rs_[K + 1]; ++b) {
          const int J = cols_[b];
          while (a < r1 && cols_[a] < J) ++a;
          if (a == r1) break;
          if (cols_[a] == J) {
            U = stored(b);
            wblk(a).noalias() -= LIK.lazyProduct(U);
          }
        }
      }
      auto DI = wblk(diag_[i]);
      tmp = Eigen::PartialPivLU<Mat>(DI).inverse();
      if (!tmp.allFinite()) throw NumericalError("block ILU: singular pivot block in row " + std::to_string(i));
      DI = tmp;
      for (size_t t = 0; t < work.size(); ++t) vals[static_cast<size_t>(r0) * bs + t] = static_cast<T>(work[t]);
    }
  });
}

namespace {
/// Forward and backward block substitution on z (in the factor's block order), in scalar type T.
template <class T>
void ilu_solve(int n, int nb, const std::vector<long long>& rs, const std::vector<int>& cols,
               const std::vector<long long>& diag, const T* vals, T* z) {
  const size_t bs = static_cast<size_t>(nb) * nb;
  dispatch_block_size(nb, [&](auto NBc) {
    constexpr int NB = decltype(NBc)::value;
    using Mat = Eigen::Matrix<T, NB, NB>;
    using Vec = Eigen::Matrix<T, NB, 1>;
    auto seg = [&](int I) { return Eigen::Map<Vec>(z + static_cast<size_t>(I) * nb, nb); };
    auto blk = [&](long long k) { return Eigen::Map<const Mat>(vals + k * bs, nb, nb); };
    Vec acc(nb), t(nb);
    for (int I = 0; I < n; ++I) {  // L y = r (unit block-lower)
      acc = seg(I);
      for (long long k = rs[I]; k < diag[I]; ++k) acc.noalias() -= blk(k) * seg(cols[k]);
      seg(I) = acc;
    }
    for (int I = n - 1; I >= 0; --I) {  // U z = y, diagonal blocks stored inverted
      acc = seg(I);
      for (long long k = diag[I] + 1; k < rs[I + 1]; ++k) acc.noalias() -= blk(k) * seg(cols[k]);
      t.noalias() = blk(diag[I]) * acc;
      seg(I) = t;
    }
  });
}
}  // namespace

void BlockILU0::apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) const {
  const int n = n_, nb = nb_;
  const Eigen::Index N = r.size();
  // Gather in elimination order.
  auto src = [&](int i) { return order_.empty() ? i : order_[i]; };
  z.resize(N);
  if (!single_.empty()) {
    Eigen::VectorXf y(N);
    for (int i = 0; i < n; ++i)
      y.segment(static_cast<Eigen::Index>(i) * nb, nb) = r.segment(static_cast<Eigen::Index>(src(i)) * nb, nb).cast<float>();
    ilu_solve<float>(n, nb, rs_, cols_, diag_, single_.data(), y.data());
    for (int i = 0; i < n; ++i)
      z.segment(static_cast<Eigen::Index>(src(i)) * nb, nb) = y.segment(static_cast<Eigen::Index>(i) * nb, nb).cast<double>();
    return;
  }
  Eigen::VectorXd y(N);
  for (int i = 0; i < n; ++i)
    y.segment(static_cast<Eigen::Index>(i) * nb, nb) = r.segment(static_cast<Eigen::Index>(src(i)) * nb, nb);
  ilu_solve<double>(n, nb, rs_, cols_, diag_, double_.data(), y.data());
  for (int i = 0; i < n; ++i)
    z.segment(static_cast<Eigen::Index>(src(i)) * nb, nb) = y.segment(static_cast<Eigen::Index>(i) * nb, nb);
}

// ---------------------------------------------------------------------------- block Jacobi

void BlockJacobi::compute(const BlockSparseMatrix& A) {
  nb_ = A.block_size();
  const int n = A.block_rows();
  inv_.assign(static_cast<size_t>(n) * nb_ * nb_, 0.0);
#pragma omp parallel for schedule(static)
  for (int I = 0; I < n; ++I) {
    long long k = A.find(I, I);
    MapM out(inv_.data() + static_cast<size_t>(I) * nb_ * nb_, nb_, nb_);
    if (k < 0) {
      out.setIdentity();
      continue;
    }
    out = Eigen::PartialPivLU<Eigen::MatrixXd>(CMapM(A.block(k), nb_, nb_)).inverse();
  }
}

void BlockJacobi::apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) const {
  z.resize(r.size());
  const int n = static_cast<int>(r.size() / nb_);
#pragma omp parallel for schedule(static)
  for (int I = 0; I < n; ++I)
    z.segment(static_cast<Eigen::Index>(I) * nb_, nb_).noalias() =
        CMapM(inv_.data() + static_cast<size_t>(I) * nb_ * nb_, nb_, nb_) *
        r.segment(static_cast<Eigen::Index>(I) * nb_, nb_);
}

}  // namespace quadapt
