// Block ILU(0): the defining property of the factorisation, checked through apply() alone.
// M = L U is the matrix whose inverse apply() computes; ILU(0) means M agrees with A on every
// block of A's pattern (the fill-in lands outside it), in the given elimination order.
#include <doctest/doctest.h>

#include <Eigen/LU>
#include <vector>

#include "case/case.hpp"
#include "dg/block_matrix.hpp"
#include "dg/discretization.hpp"
#include "dg_test_meshes.hpp"
#include "../worst.hpp"

using namespace quadapt;

namespace {

/// The dense matrix M with apply(r) = M^-1 r (columns of M^-1 from unit vectors, then inverted).
Eigen::MatrixXd preconditioner_matrix(const BlockILU0& ilu, int n) {
  Eigen::MatrixXd Minv(n, n);
  Eigen::VectorXd e = Eigen::VectorXd::Zero(n), z;
  for (int j = 0; j < n; ++j) {
    e[j] = 1;
    ilu.apply(e, z);
    Minv.col(j) = z;
    e[j] = 0;
  }
  return Minv.inverse();
}

/// max over the blocks (I, J) of A's pattern of |M_IJ - A_IJ|, relative to max |A|.
double pattern_mismatch(const BlockSparseMatrix& B, const Eigen::MatrixXd& M) {
  const int nb = B.block_size();
  double worst = 0, scale = 0;
  for (int I = 0; I < B.block_rows(); ++I)
    for (long long k = B.row_start()[I]; k < B.row_start()[I + 1]; ++k) {
      Eigen::Map<const Eigen::MatrixXd> AIJ(B.block(k), nb, nb);
      const int J = B.cols()[k];
      worst = quadapt_test::worst_of(worst, (M.block(I * nb, J * nb, nb, nb) - AIJ).cwiseAbs().maxCoeff());
      scale = std::max(scale, AIJ.cwiseAbs().maxCoeff());
    }
  return worst / scale;
}

}  // namespace

TEST_CASE("block ILU(0): L U equals A on A's block pattern, in any elimination order, double and single") {
  Case cs = parse_case(R"J({"exact": "sin(3*x)*y", "diffusion": [[0.2, 0.05], [0.05, 0.1]], "advection": [1, 2]})J",
                       "ilu.json");
  // Non-conforming perturbed mesh: rows with 5-6 blocks, so there is fill-in to drop.
  Mesh m = dgtest::half_split(make_perturbed_quads(3, 3, 0.2, 5));
  for (int p : {1, 2}) {
    DGDiscretization dg(m, cs, p);
    BlockSparseMatrix B;
    Eigen::VectorXd b;
    dg.assemble(B, b);
    const int n = B.rows();
    const Eigen::MatrixXd A = Eigen::MatrixXd(B.to_csc());
    std::vector<int> natural, shuffled(B.block_rows());
    for (int i = 0; i < B.block_rows(); ++i) shuffled[i] = (5 * i + 2) % B.block_rows();
    for (const auto* order : {&natural, &shuffled}) {
      CAPTURE(p);
      CAPTURE(order->size());
      BlockILU0 d, s;
      d.compute(B, *order, false);
      s.compute(B, *order, true);
      const Eigen::MatrixXd Md = preconditioner_matrix(d, n), Ms = preconditioner_matrix(s, n);
      CHECK(pattern_mismatch(B, Md) < 1e-12);
      CHECK(pattern_mismatch(B, Ms) < 1e-5);  // factors rounded to single precision
      // Not the exact inverse: ILU(0) drops fill-in on these meshes.
      CHECK((Md - A).cwiseAbs().maxCoeff() > 1e-8 * A.cwiseAbs().maxCoeff());
    }
  }
}
