#include "dg/two_level.hpp"

#include <omp.h>

#include <Eigen/UmfPackSupport>
#include <exception>

#include "core/error.hpp"
#include "fem/basis.hpp"
#include "dg/block_dispatch.hpp"

namespace quadapt {

VertexCoarseSpace make_vertex_coarse_space(const Mesh& mesh, int p) {
  VertexCoarseSpace cs;
  cs.num_coarse = mesh.num_nodes();
  cs.nb = (p + 1) * (p + 1);
  cs.vert.resize(mesh.num_cells());
  for (int c = 0; c < mesh.num_cells(); ++c) {
    if (!mesh.cells[c].is_quad()) throw InputError("mesh: the DG coarse space needs quads");
    for (int k = 0; k < 4; ++k) cs.vert[c][k] = mesh.cells[c].v[k];
  }
  LagrangeBasis1D b(p);
  const auto& x = b.nodes();
  cs.shape.resize(cs.nb, 4);
  for (int j = 0; j <= p; ++j)
    for (int i = 0; i <= p; ++i) {
      const int a = i + (p + 1) * j;
      const double xi = x[i], eta = x[j];
      cs.shape(a, 0) = 0.25 * (1 - xi) * (1 - eta);
      cs.shape(a, 1) = 0.25 * (1 + xi) * (1 - eta);
      cs.shape(a, 2) = 0.25 * (1 + xi) * (1 + eta);
      cs.shape(a, 3) = 0.25 * (1 - xi) * (1 + eta);
    }
  return cs;
}

struct TwoLevelPreconditioner::Impl {
  const BlockSparseMatrix* A = nullptr;
  VertexCoarseSpace coarse;
  BlockILU0 ilu;       ///< pre-smoother: elimination in the given order
  BlockILU0 ilu_back;  ///< post-smoother: the same order reversed
  Eigen::SparseMatrix<double> Ac;  // UmfPackLU keeps a reference to its matrix
  Eigen::UmfPackLU<Eigen::SparseMatrix<double>> lu;
  bool post = true;
};

TwoLevelPreconditioner::TwoLevelPreconditioner() : impl_(std::make_unique<Impl>()) {}
TwoLevelPreconditioner::~TwoLevelPreconditioner() = default;

void TwoLevelPreconditioner::compute(const BlockSparseMatrix& A, const VertexCoarseSpace& coarse, bool post_smooth,
                                     const std::vector<int>& order) {
  Impl& I = *impl_;
  if (A.block_size() != coarse.nb || A.block_rows() != static_cast<int>(coarse.vert.size()))
    throw NumericalError("two-level preconditioner: coarse space does not match the matrix blocks");
  I.A = &A;
  I.coarse = coarse;
  I.post = post_smooth;
  std::vector<int> back;
  if (post_smooth) {
    back.assign(order.rbegin(), order.rend());
    if (back.empty()) {
      back.resize(static_cast<size_t>(A.block_rows()));
      for (size_t i = 0; i < back.size(); ++i) back[i] = static_cast<int>(back.size() - 1 - i);
    }
  }
  // The two factorisations are sequential and independent of each other: with two threads each
  // gets one (the same factors bit for bit as one after the other). An exception inside an
  // OpenMP region must not leave it: each section keeps its own and the first is rethrown.
  std::exception_ptr err[2];
#pragma omp parallel sections num_threads(2) if (post_smooth && omp_get_max_threads() > 1)
  {
#pragma omp section
    {
      try {
        I.ilu.compute(A, order);
      } catch (...) {
        err[0] = std::current_exception();
      }
    }
#pragma omp section
    {
      try {
        if (post_smooth) I.ilu_back.compute(A, back);
      } catch (...) {
        err[1] = std::current_exception();
      }
    }
  }
  for (const auto& e : err)
    if (e) std::rethrow_exception(e);

  // A_c = P^T A P, block by block: (S^T A_IJ S) scattered to the vertices of I and J.
  const int n = A.block_rows(), nb = A.block_size();
  const auto& rs = A.row_start();
  const auto& cols = A.cols();
  std::vector<Eigen::Matrix4d> local(static_cast<size_t>(A.num_blocks()));
  dispatch_block_size(nb, [&](auto NBc) {
    constexpr int NB = decltype(NBc)::value;
    using Shape = Eigen::Matrix<double, NB, 4>;
    const Shape S = coarse.shape;
#pragma omp parallel for schedule(static)
    for (int r = 0; r < n; ++r)
      for (long long k = rs[r]; k < rs[r + 1]; ++k) {
        const Shape AS = Eigen::Map<const Eigen::Matrix<double, NB, NB>>(A.block(k), nb, nb).lazyProduct(S);
        local[k].noalias() = S.transpose().lazyProduct(AS);
      }
  });
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(local.size() * 16);
  for (int r = 0; r < n; ++r)
    for (long long k = rs[r]; k < rs[r + 1]; ++k)
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) trip.emplace_back(coarse.vert[r][a], coarse.vert[cols[k]][b], local[k](a, b));
  Eigen::SparseMatrix<double>& Ac = I.Ac;
  Ac.resize(coarse.num_coarse, coarse.num_coarse);
  Ac.setFromTriplets(trip.begin(), trip.end());
  // Nodes that belong to no cell would give empty rows: put a 1 on their diagonal.
  for (int i = 0; i < coarse.num_coarse; ++i)
    if (Ac.col(i).nonZeros() == 0) Ac.coeffRef(i, i) = 1.0;
  Ac.makeCompressed();
  I.lu.compute(Ac);
  if (I.lu.info() != Eigen::Success) throw NumericalError("two-level preconditioner: singular coarse matrix");
}

void TwoLevelPreconditioner::apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) const {
  const Impl& I = *impl_;
  const int n = I.A->block_rows(), nb = I.A->block_size();
  I.ilu.apply(r, z);
  Eigen::VectorXd t;
  I.A->multiply(z, t);
  Eigen::VectorXd rr = r - t;
  Eigen::VectorXd rc = Eigen::VectorXd::Zero(I.coarse.num_coarse);
  Eigen::VectorXd xc;
  dispatch_block_size(nb, [&](auto NBc) {
    constexpr int NB = decltype(NBc)::value;
    using Shape = Eigen::Matrix<double, NB, 4>;
    using Vec = Eigen::Matrix<double, NB, 1>;
    const Shape S = I.coarse.shape;
    for (int c = 0; c < n; ++c) {  // r_c = P^T rr (sequential: vertices are shared)
      const Eigen::Vector4d v = S.transpose() * Eigen::Map<const Vec>(rr.data() + static_cast<Eigen::Index>(c) * nb, nb);
      for (int k = 0; k < 4; ++k) rc[I.coarse.vert[c][k]] += v[k];
    }
    xc = I.lu.solve(rc);
#pragma omp parallel for schedule(static)
    for (int c = 0; c < n; ++c) {  // z += P x_c
      Eigen::Vector4d v;
      for (int k = 0; k < 4; ++k) v[k] = xc[I.coarse.vert[c][k]];
      Eigen::Map<Vec>(z.data() + static_cast<Eigen::Index>(c) * nb, nb).noalias() += S * v;
    }
  });
  if (!I.post) return;
  I.A->multiply(z, t);
  rr = r - t;
  Eigen::VectorXd w;
  I.ilu_back.apply(rr, w);
  z += w;
}

}  // namespace quadapt
