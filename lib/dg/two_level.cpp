#include "dg/two_level.hpp"

#include <omp.h>

#include <Eigen/UmfPackSupport>
#include <algorithm>
#include <cstdint>
#include <exception>
#include <unordered_map>

#include "core/error.hpp"
#include "fem/basis.hpp"
#include "dg/block_dispatch.hpp"

namespace quadapt {

int coarse_degree(int p, int requested) { return requested > 0 ? std::min(requested, p) : std::min(p, 2); }

CoarseSpace make_coarse_space(const Mesh& mesh, int p, int degree) {
  if (degree < 1 || degree > p)
    throw Error("make_coarse_space: coarse degree " + std::to_string(degree) + " outside 1.." + std::to_string(p));
  const int q = degree, n1 = q + 1, n = mesh.num_cells();
  CoarseSpace cs;
  cs.degree = q;
  cs.nb = (p + 1) * (p + 1);
  cs.m = n1 * n1;
  cs.dof.assign(static_cast<size_t>(n) * cs.m, -1);
  // Mesh nodes first (a node in no cell gets a 1 on the coarse diagonal), then, cell by cell, the
  // inner points of its edges not met before and its own inner points (one counter for both).
  int next = mesh.num_nodes();
  std::unordered_map<std::uint64_t, int> edge_base;
  for (int c = 0; c < n; ++c) {
    const Cell& cell = mesh.cells[c];
    if (!cell.is_quad()) throw InputError("mesh: the DG coarse space needs quads");
    const std::array<int, 4> v = {cell.v[0], cell.v[1], cell.v[2], cell.v[3]};
    for (int j = 0; j < n1; ++j)
      for (int i = 0; i < n1; ++i) {
        int g;
        const bool end_i = i == 0 || i == q, end_j = j == 0 || j == q;
        if (end_i && end_j) {  // corners (-1,-1), (1,-1), (1,1), (-1,1) = v0..v3
          g = v[j == 0 ? (i == 0 ? 0 : 1) : (i == q ? 2 : 3)];
        } else if (end_i || end_j) {
          // local edge e runs from v[e] to v[e+1]; t = the point's place along it
          int e, t;
          if (j == 0) {
            e = 0, t = i;
          } else if (i == q) {
            e = 1, t = j;
          } else if (j == q) {
            e = 2, t = q - i;
          } else {
            e = 3, t = q - j;
          }
          const int va = v[e], vb = v[(e + 1) % 4];
          const std::uint64_t key = (static_cast<std::uint64_t>(std::min(va, vb)) << 32) | static_cast<std::uint32_t>(std::max(va, vb));
          auto it = edge_base.find(key);
          if (it == edge_base.end()) {
            it = edge_base.emplace(key, next).first;
            next += q - 1;
          }
          g = it->second + (va < vb ? t : q - t) - 1;  // counted from the edge's lower node
        } else {
          g = next++;
        }
        cs.dof[static_cast<size_t>(c) * cs.m + i + n1 * j] = g;
      }
  }
  cs.num_coarse = next;
  // P_K(a, k) = l^q_kx(x_i) l^q_ky(x_j): the degree-q GLL Lagrange polynomials at the DG nodes
  const LagrangeBasis1D fine(p), coarse(q);
  Eigen::MatrixXd l(p + 1, n1);
  for (int i = 0; i <= p; ++i)
    for (int k = 0; k <= q; ++k) {
      double v = 1;
      for (int o = 0; o <= q; ++o)
        if (o != k) v *= (fine.nodes()[i] - coarse.nodes()[o]) / (coarse.nodes()[k] - coarse.nodes()[o]);
      l(i, k) = v;
    }
  cs.shape.resize(cs.nb, cs.m);
  for (int j = 0; j <= p; ++j)
    for (int i = 0; i <= p; ++i)
      for (int ky = 0; ky <= q; ++ky)
        for (int kx = 0; kx <= q; ++kx) cs.shape(i + (p + 1) * j, kx + n1 * ky) = l(i, kx) * l(j, ky);
  return cs;
}

Eigen::SparseMatrix<double> galerkin_coarse_matrix(const BlockSparseMatrix& A, const CoarseSpace& coarse) {
  if (A.block_size() != coarse.nb || static_cast<size_t>(A.block_rows()) * coarse.m != coarse.dof.size())
    throw NumericalError("two-level preconditioner: coarse space does not match the matrix blocks");
  // A_c = P^T A P, block by block: S^T A_IJ S (m x m) scattered to the coarse values of I and J,
  // straight into compressed columns. Its pattern is that of the products' nonzero entries: a DG
  // face block couples only the values on its face to the rest (GLL nodal bases vanish exactly on
  // the faces they are not on), and so do the coarse blocks; the full m x m pairs of neighbouring
  // cells would give UMFPACK 2-4x the fill (measured: 5.0 against 1.2 s at p = 2, 65k DOFs).
  const int n = A.block_rows(), nb = A.block_size(), m = coarse.m, nc = coarse.num_coarse;
  const auto& rs = A.row_start();
  const auto& cols = A.cols();
  auto dofs = [&](int c) { return coarse.dof.data() + static_cast<size_t>(c) * m; };
  // Calls f(r, k, S^T A_k S) for every block k of row r in block order; the products of a chunk
  // of rows are made in parallel (the same values, and the same order of f's calls, with any
  // thread count).
  auto for_each_product = [&](auto&& f) {
    constexpr int kChunk = 512;
    std::vector<Eigen::MatrixXd> local;
    for (int r0 = 0; r0 < n; r0 += kChunk) {
      const int r1 = std::min(n, r0 + kChunk);
      const long long k0 = rs[r0], k1 = rs[r1];
      local.resize(static_cast<size_t>(k1 - k0));
      dispatch_block_size(nb, [&](auto NBc) {
        constexpr int NB = decltype(NBc)::value;
        using Shape = Eigen::Matrix<double, NB, Eigen::Dynamic>;
        const Shape S = coarse.shape;
#pragma omp parallel for schedule(static)
        for (long long k = k0; k < k1; ++k) {
          const Shape AS = Eigen::Map<const Eigen::Matrix<double, NB, NB>>(A.block(k), nb, nb) * S;
          local[k - k0].noalias() = S.transpose() * AS;
        }
      });
      for (int r = r0; r < r1; ++r)
        for (long long k = rs[r]; k < rs[r + 1]; ++k) f(r, k, local[k - k0]);
    }
  };
  std::vector<std::vector<int>> col_rows(static_cast<size_t>(nc));
  for_each_product([&](int r, long long k, const Eigen::MatrixXd& L) {
    const int *gi = dofs(r), *gj = dofs(cols[k]);
    for (int b = 0; b < m; ++b)
      for (int a = 0; a < m; ++a)
        if (L(a, b) != 0) col_rows[gj[b]].push_back(gi[a]);
  });
  std::vector<int> col_start(static_cast<size_t>(nc) + 1, 0), rows;
  std::vector<char> empty(static_cast<size_t>(nc), 0);
  for (int g = 0; g < nc; ++g) {
    std::vector<int>& c = col_rows[g];
    if (c.empty()) {  // a node in no cell (or a zero column): a 1 on the diagonal
      c.push_back(g);
      empty[g] = 1;
    }
    std::sort(c.begin(), c.end());
    c.erase(std::unique(c.begin(), c.end()), c.end());
    rows.insert(rows.end(), c.begin(), c.end());
    col_start[g + 1] = static_cast<int>(rows.size());
    std::vector<int>().swap(c);
  }
  std::vector<double> vals(rows.size(), 0.0);
  for (int g = 0; g < nc; ++g)
    if (empty[g]) vals[col_start[g]] = 1.0;
  for_each_product([&](int r, long long k, const Eigen::MatrixXd& L) {
    const int *gi = dofs(r), *gj = dofs(cols[k]);
    for (int b = 0; b < m; ++b) {
      const int* lo = rows.data() + col_start[gj[b]];
      const int* hi = rows.data() + col_start[gj[b] + 1];
      for (int a = 0; a < m; ++a)
        if (L(a, b) != 0) {
          const int* at = std::lower_bound(lo, hi, gi[a]);
          if (at == hi || *at != gi[a]) throw NumericalError("two-level preconditioner: coarse pattern mismatch");
          vals[at - rows.data()] += L(a, b);
        }
    }
  });
  return Eigen::Map<const Eigen::SparseMatrix<double>>(nc, nc, static_cast<Eigen::Index>(vals.size()), col_start.data(),
                                                     rows.data(), vals.data());
}

struct TwoLevelPreconditioner::Impl {
  const BlockSparseMatrix* A = nullptr;
  CoarseSpace coarse;
  BlockILU0 ilu;       ///< pre-smoother: elimination in the given order
  BlockILU0 ilu_back;  ///< post-smoother: the same order reversed
  Eigen::SparseMatrix<double> Ac;  // UmfPackLU keeps a reference to its matrix
  Eigen::UmfPackLU<Eigen::SparseMatrix<double>> lu;
  bool post = true;
};

TwoLevelPreconditioner::TwoLevelPreconditioner() : impl_(std::make_unique<Impl>()) {}
TwoLevelPreconditioner::~TwoLevelPreconditioner() = default;

void TwoLevelPreconditioner::compute(const BlockSparseMatrix& A, const CoarseSpace& coarse, bool post_smooth,
                                     const std::vector<int>& order) {
  Impl& I = *impl_;
  if (A.block_size() != coarse.nb || static_cast<size_t>(A.block_rows()) * coarse.m != coarse.dof.size())
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

  I.Ac = galerkin_coarse_matrix(A, coarse);
  // One step of iterative refinement (UMFPACK's default is up to 2; each costs a coarse solve and
  // a product): without any, the same Q_2 system factorised with OpenBLAS instead of the
  // reference BLAS gave a coarse correction poor enough to double GMRES's iterations (56 against
  // 28 at p = 3, 116k DOFs); one step gives 28 with either.
  I.lu.umfpackControl()(UMFPACK_IRSTEP) = 1;
  I.lu.compute(I.Ac);
  if (I.lu.info() != Eigen::Success) throw NumericalError("two-level preconditioner: singular coarse matrix");
}

void TwoLevelPreconditioner::apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) const {
  const Impl& I = *impl_;
  const int n = I.A->block_rows(), nb = I.A->block_size(), m = I.coarse.m;
  I.ilu.apply(r, z);
  Eigen::VectorXd t;
  I.A->multiply(z, t);
  Eigen::VectorXd rr = r - t;
  Eigen::VectorXd rc = Eigen::VectorXd::Zero(I.coarse.num_coarse);
  Eigen::VectorXd xc;
  dispatch_block_size(nb, [&](auto NBc) {
    constexpr int NB = decltype(NBc)::value;
    using Shape = Eigen::Matrix<double, NB, Eigen::Dynamic>;
    using Vec = Eigen::Matrix<double, NB, 1>;
    const Shape S = I.coarse.shape;
    Eigen::VectorXd v(m);
    for (int c = 0; c < n; ++c) {  // r_c = P^T rr (sequential: coarse values are shared)
      v.noalias() = S.transpose() * Eigen::Map<const Vec>(rr.data() + static_cast<Eigen::Index>(c) * nb, nb);
      const int* g = I.coarse.dof.data() + static_cast<size_t>(c) * m;
      for (int k = 0; k < m; ++k) rc[g[k]] += v[k];
    }
    xc = I.lu.solve(rc);
#pragma omp parallel
    {
      Eigen::VectorXd w(m);
#pragma omp for schedule(static)
      for (int c = 0; c < n; ++c) {  // z += P x_c
        const int* g = I.coarse.dof.data() + static_cast<size_t>(c) * m;
        for (int k = 0; k < m; ++k) w[k] = xc[g[k]];
        Eigen::Map<Vec>(z.data() + static_cast<Eigen::Index>(c) * nb, nb).noalias() += S * w;
      }
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
