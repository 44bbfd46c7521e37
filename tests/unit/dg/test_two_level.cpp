// The two-level preconditioner's smoothers (lib/dg/two_level.hpp): a forward block-ILU(0) sweep
// before the coarse correction and the reversed sweep after it. On an adapted, stretched mesh
// the same forward sweep in both places made GMRES slow: the fixture (step 3 of the
// boundary-layer feature loop, p = 1, L_p-CVT path, 901 cells up to ~20:1) needed 38 iterations
// with it and needs 15 with the reversed post-sweep; on the oblique-layer case of docs/dgsolve.md
// the old smoother did not converge at all. Structured grids need the same count either way.
#include <doctest/doctest.h>

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "case/case.hpp"
#include "core/error.hpp"
#include "dg/discretization.hpp"
#include "dg/linear_solver.hpp"
#include "dg/solve.hpp"
#include "dg/two_level.hpp"
#include "fem/basis.hpp"
#include "io/msh.hpp"
#include "../worst.hpp"

using namespace quadapt;

namespace {

struct TwoLevelRun {
  LinearSolveInfo info;
  double error_vs_direct = 0;
};

/// The block system of (m, cs, p) and gmres-2level's options as dgsolve sets them.
struct TwoLevelSystem {
  BlockSparseMatrix B;
  Eigen::VectorXd b;
  CoarseSpace vc;
  LinearSolverOptions o;
  TwoLevelSystem(const DGDiscretization& dg, const Mesh& m, const Case& cs, int p) : vc(make_coarse_space(m, p, coarse_degree(p, 0))) {
    dg.assemble(B, b);
    o.kind = LinearSolverKind::GmresTwoLevel;
    o.coarse = &vc;
    o.block_size = dg.dofs_per_cell();
    o.block_order = sweep_order(m, cs.advection);  // as dgsolve orders the cells
  }
  TwoLevelSystem(const TwoLevelSystem&) = delete;  // o.coarse points into this object
};

TwoLevelRun run_two_level(const Mesh& m, const Case& cs, int p) {
  DGDiscretization dg(m, cs, p);
  SparseMatrixCSC A;
  Eigen::VectorXd b2;
  dg.assemble(A, b2);
  LinearSolverOptions direct;
  direct.kind = LinearSolverKind::UmfPack;
  const Eigen::VectorXd ref = solve_linear(A, b2, direct);
  const TwoLevelSystem sys(dg, m, cs, p);
  TwoLevelRun r;
  const Eigen::VectorXd x = solve_linear(sys.B, sys.b, sys.o, &r.info);
  r.error_vs_direct = (x - ref).norm() / ref.norm();
  return r;
}

}  // namespace

TEST_CASE("two-level: the reversed post-sweep keeps GMRES fast on an adapted stretched mesh") {
  const std::string src = QUADAPT_SOURCE_DIR;
  const Mesh m = read_msh(src + "/tests/fixtures/dg/boundary-layer-p1-step3.msh");
  REQUIRE(m.num_cells() == 901);
  const Case cs = load_case(src + "/examples/cases/boundary-layer.json");
  const TwoLevelRun r = run_two_level(m, cs, 1);
  CAPTURE(r.info.iterations);
  CHECK(r.error_vs_direct < 1e-9);
  CHECK(r.info.iterations <= 22);  // 15 measured; 38 with the forward sweep twice
}

// q = 2 by default: on stretched cells the continuous Q_1 space lacks the modes that are smooth
// across a stack of thin cells and of high degree along them (two_level.hpp).
TEST_CASE("two-level: the Q_2 coarse space keeps GMRES short at p = 3 on the stretched mesh") {
  const std::string src = QUADAPT_SOURCE_DIR;
  const Mesh m = read_msh(src + "/tests/fixtures/dg/boundary-layer-p1-step3.msh");
  const Case cs = load_case(src + "/examples/cases/boundary-layer.json");
  const DGDiscretization dg(m, cs, 3);
  int its[2] = {0, 0};
  for (int q : {1, 2}) {
    TwoLevelSystem sys(dg, m, cs, 3);
    sys.vc = make_coarse_space(m, 3, q);
    LinearSolveInfo info;
    solve_linear(sys.B, sys.b, sys.o, &info);
    CHECK(info.coarse_degree == q);
    its[q - 1] = info.iterations;
  }
  CAPTURE(its[0]);
  CAPTURE(its[1]);
  CHECK(coarse_degree(3, 0) == 2);
  CHECK(its[1] <= 34);            // 26 measured
  CHECK(its[0] >= its[1] + 15);   // Q_1: 49
}

// Continuity is what makes the coarse space immune to the penalty: the prolonged DG values of
// any coarse vector agree wherever two cells' nodes coincide, whatever the cells' orientations
// (the fixture's cells meet their neighbours' edges in both directions).
TEST_CASE("two-level: the Q_q coarse space is continuous and counts its points") {
  const std::string src = QUADAPT_SOURCE_DIR;
  const Mesh grid = make_structured_quads(3, 2);  // 12 nodes, 17 edges, 6 cells
  CHECK(make_coarse_space(grid, 3, 1).num_coarse == 12);
  CHECK(make_coarse_space(grid, 3, 2).num_coarse == 12 + 17 + 6);
  CHECK(make_coarse_space(grid, 3, 3).num_coarse == 12 + 2 * 17 + 4 * 6);
  CHECK_THROWS_AS(make_coarse_space(grid, 2, 3), Error);
  CHECK(coarse_degree(1, 0) == 1);
  CHECK(coarse_degree(5, 0) == 2);
  CHECK(coarse_degree(2, 4) == 2);
  const Mesh m = read_msh(src + "/tests/fixtures/dg/boundary-layer-p1-step3.msh");
  for (int p : {2, 4})
    for (int q = 1; q <= std::min(p, 3); ++q) {
      CAPTURE(p);
      CAPTURE(q);
      const CoarseSpace cs = make_coarse_space(m, p, q);
      CHECK((cs.shape.rowwise().sum().array() - 1).abs().maxCoeff() < 1e-13);  // partition of unity
      Eigen::VectorXd x(cs.num_coarse);
      for (int g = 0; g < cs.num_coarse; ++g) x[g] = std::sin(1.7 * g + 0.3);
      const LagrangeBasis1D b(p);
      std::map<std::pair<long long, long long>, double> at;  // node position (1e-9 grid) -> value
      double worst = 0;
      int shared = 0;
      for (int c = 0; c < m.num_cells(); ++c) {
        Eigen::VectorXd xc(cs.m);
        for (int k = 0; k < cs.m; ++k) xc[k] = x[cs.dof[static_cast<size_t>(c) * cs.m + k]];
        const Eigen::VectorXd u = cs.shape * xc;
        for (int j = 0; j <= p; ++j)
          for (int i = 0; i <= p; ++i) {
            const double xi = b.nodes()[i], eta = b.nodes()[j];
            const double w[4] = {(1 - xi) * (1 - eta) / 4, (1 + xi) * (1 - eta) / 4, (1 + xi) * (1 + eta) / 4,
                                 (1 - xi) * (1 + eta) / 4};
            Eigen::Vector2d pos = Eigen::Vector2d::Zero();
            for (int k = 0; k < 4; ++k) pos += w[k] * m.nodes[m.cells[c].v[k]];
            const auto key = std::make_pair(std::llround(pos.x() * 1e9), std::llround(pos.y() * 1e9));
            const auto [it, fresh] = at.emplace(key, u[i + (p + 1) * j]);
            if (!fresh) {
              ++shared;
              worst = quadapt_test::worst_of(worst, std::abs(it->second - u[i + (p + 1) * j]));
            }
          }
      }
      CHECK(shared > 0);
      CHECK(worst < 1e-12);
    }
}

// The coarse matrix assembled on its products' pattern is the dense P^T A P (P: the prolongation
// of make_coarse_space), entry for entry; a scatter into the wrong slot would only slow GMRES down.
TEST_CASE("two-level: the Galerkin coarse matrix is P^T A P") {
  const std::string src = QUADAPT_SOURCE_DIR;
  Mesh m = make_structured_quads(4, 3);
  for (Vec2& x : m.nodes) x += Vec2(0.07 * std::sin(7 * x.y() + 1), 0.05 * std::cos(5 * x.x()));  // not affine
  const Case cs = load_case(src + "/examples/cases/sshock.json");
  for (int p : {1, 3})
    for (int q = 1; q <= std::min(p, 2); ++q) {
      CAPTURE(p);
      CAPTURE(q);
      const DGDiscretization dg(m, cs, p);
      BlockSparseMatrix B;
      Eigen::VectorXd b;
      dg.assemble(B, b);
      const CoarseSpace c = make_coarse_space(m, p, q);
      Eigen::MatrixXd P = Eigen::MatrixXd::Zero(dg.num_dofs(), c.num_coarse);
      for (int k = 0; k < m.num_cells(); ++k)
        for (int j = 0; j < c.m; ++j) P.block(k * c.nb, c.dof[k * c.m + j], c.nb, 1) += c.shape.col(j);
      const Eigen::MatrixXd A = Eigen::MatrixXd(B.to_csc());
      const Eigen::MatrixXd ref = P.transpose() * A * P;
      const Eigen::MatrixXd Ac = Eigen::MatrixXd(galerkin_coarse_matrix(B, c));
      CHECK((Ac - ref).cwiseAbs().maxCoeff() <= 1e-12 * ref.cwiseAbs().maxCoeff());
      CHECK(Ac.rows() == (q == 1 ? 20 : 20 + 31 + 12));
    }
}

TEST_CASE("two-level: structured grid, the count is the smoother-independent 10-20") {
  const Case cs = load_case(std::string(QUADAPT_SOURCE_DIR) + "/examples/cases/smooth.json");
  const TwoLevelRun r = run_two_level(make_structured_quads(24, 24), cs, 2);
  CAPTURE(r.info.iterations);
  CHECK(r.error_vs_direct < 1e-9);
  CHECK(r.info.iterations <= 20);
}

// The two block ILU(0) factorisations run side by side when two threads are available
// (two_level.cpp); each is sequential, so the preconditioner, the iterations and the solution
// are the same bits with one thread or two.
TEST_CASE("two-level: the same solution bit for bit with 1 and 2 threads") {
  const std::string src = QUADAPT_SOURCE_DIR;
  const Mesh m = read_msh(src + "/tests/fixtures/dg/boundary-layer-p1-step3.msh");
  const Case cs = load_case(src + "/examples/cases/boundary-layer.json");
  const DGDiscretization dg(m, cs, 2);
  const TwoLevelSystem sys(dg, m, cs, 2);
  const int saved = omp_get_max_threads();
  LinearSolveInfo i1, i2;
  omp_set_num_threads(1);
  const Eigen::VectorXd x1 = solve_linear(sys.B, sys.b, sys.o, &i1);
  omp_set_num_threads(2);
  const Eigen::VectorXd x2 = solve_linear(sys.B, sys.b, sys.o, &i2);
  omp_set_num_threads(saved);
  CHECK(i1.iterations == i2.iterations);
  REQUIRE(x1.size() == x2.size());
  CHECK((x1.array() == x2.array()).all());
}

TEST_CASE("two-level: a singular pivot block is a NumericalError from either factorisation") {
  // p = 1 on a 3 x 3 grid; the middle cell's block row and column zeroed, so its pivot block is
  // zero whatever the order: both factorisations throw, one error leaves the parallel sections.
  const Mesh m = make_structured_quads(3, 3);
  const Case cs = load_case(std::string(QUADAPT_SOURCE_DIR) + "/examples/cases/smooth.json");
  DGDiscretization dg(m, cs, 1);
  BlockSparseMatrix B;
  Eigen::VectorXd b;
  dg.assemble(B, b);
  const int nb2 = B.block_size() * B.block_size();
  for (int j = 0; j < 9; ++j) {  // block row and column 4 zero: singular in any elimination order
    const long long a = B.find(4, j), c = B.find(j, 4);
    if (a >= 0) std::fill_n(B.block(a), nb2, 0.0);
    if (c >= 0) std::fill_n(B.block(c), nb2, 0.0);
  }
  CoarseSpace vc = make_coarse_space(m, 1, coarse_degree(1, 0));
  const int saved = omp_get_max_threads();
  for (int threads : {1, 2}) {
    omp_set_num_threads(threads);
    TwoLevelPreconditioner P;
    CHECK_THROWS_WITH_AS(P.compute(B, vc, true), doctest::Contains("block ILU: singular pivot block"), NumericalError);
  }
  omp_set_num_threads(saved);
}
