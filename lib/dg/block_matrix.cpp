#include "dg/block_matrix.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <stdexcept>

#include "core/error.hpp"

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

long long BlockSparseMatrix::find(int I, int J) const {
  auto b = cols_.begin() + row_start_[I], e = cols_.begin() + row_start_[I + 1];
  auto it = std::lower_bound(b, e, J);
  return (it != e && *it == J) ? static_cast<long long>(it - cols_.begin()) : -1;
}

void BlockSparseMatrix::multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  y.resize(rows());
  const int nb = nb_;
#pragma omp parallel for schedule(static)
  for (int I = 0; I < nbr_; ++I) {
    Eigen::VectorXd acc = Eigen::VectorXd::Zero(nb);
    for (long long k = row_start_[I]; k < row_start_[I + 1]; ++k)
      acc.noalias() += CMapM(block(k), nb, nb) * x.segment(static_cast<Eigen::Index>(cols_[k]) * nb, nb);
    y.segment(static_cast<Eigen::Index>(I) * nb, nb) = acc;
  }
}

// ---------------------------------------------------------------------------- block ILU(0)

void BlockILU0::compute(const BlockSparseMatrix& A) {
  LU_ = A;
  const int n = A.block_rows(), nb = A.block_size();
  const auto& rs = LU_.row_start();
  const auto& cols = LU_.cols();
  diag_.assign(n, -1);
  for (int I = 0; I < n; ++I) {
    diag_[I] = LU_.find(I, I);
    if (diag_[I] < 0) throw NumericalError("block ILU: block row " + std::to_string(I) + " has no diagonal block");
  }
  Eigen::MatrixXd tmp(nb, nb);
  for (int I = 0; I < n; ++I) {
    for (long long k = rs[I]; k < diag_[I]; ++k) {
      const int K = cols[k];
      MapM LIK(LU_.block(k), nb, nb);
      tmp.noalias() = LIK * CMapM(LU_.block(diag_[K]), nb, nb);  // diagonal stores inv(U_KK)
      LIK = tmp;
      // Row I -= L_IK * (row K beyond its diagonal), restricted to row I's pattern.
      long long a = k + 1, aend = rs[I + 1];
      for (long long b = diag_[K] + 1; b < rs[K + 1]; ++b) {
        const int J = cols[b];
        while (a < aend && cols[a] < J) ++a;
        if (a == aend) break;
        if (cols[a] == J) MapM(LU_.block(a), nb, nb).noalias() -= LIK * CMapM(LU_.block(b), nb, nb);
      }
    }
    MapM DI(LU_.block(diag_[I]), nb, nb);
    Eigen::PartialPivLU<Eigen::MatrixXd> lu(DI);
    tmp = lu.inverse();
    if (!tmp.allFinite()) throw NumericalError("block ILU: singular pivot block in row " + std::to_string(I));
    DI = tmp;
  }
}

void BlockILU0::apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) const {
  const int n = LU_.block_rows(), nb = LU_.block_size();
  const auto& rs = LU_.row_start();
  const auto& cols = LU_.cols();
  z = r;
  Eigen::VectorXd acc(nb);
  for (int I = 0; I < n; ++I) {
    acc = z.segment(static_cast<Eigen::Index>(I) * nb, nb);
    for (long long k = rs[I]; k < diag_[I]; ++k)
      acc.noalias() -= CMapM(LU_.block(k), nb, nb) * z.segment(static_cast<Eigen::Index>(cols[k]) * nb, nb);
    z.segment(static_cast<Eigen::Index>(I) * nb, nb) = acc;
  }
  Eigen::VectorXd t(nb);
  for (int I = n - 1; I >= 0; --I) {
    acc = z.segment(static_cast<Eigen::Index>(I) * nb, nb);
    for (long long k = diag_[I] + 1; k < rs[I + 1]; ++k)
      acc.noalias() -= CMapM(LU_.block(k), nb, nb) * z.segment(static_cast<Eigen::Index>(cols[k]) * nb, nb);
    t.noalias() = CMapM(LU_.block(diag_[I]), nb, nb) * acc;
    z.segment(static_cast<Eigen::Index>(I) * nb, nb) = t;
  }
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
