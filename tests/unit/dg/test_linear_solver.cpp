// The direct solvers' residual check (linear_solver.cpp, kDirectResidualLimit): an LU of a matrix
// that is singular up to rounding can finish without a zero pivot and return an arbitrary x; the
// residual ||b - A x|| / ||b|| tells, and solve_linear must throw NumericalError instead of
// returning it. The matrix: a weighted graph Laplacian (rows summing to zero only up to rounding,
// as in a pure-diffusion case without a Dirichlet boundary) with a right-hand side that is not
// in its range (its entries do not sum to zero).
#include <doctest/doctest.h>

#include <random>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "dg/linear_solver.hpp"

using namespace quadapt;

namespace {

/// n x n path-graph Laplacian with weights in (0.1, 1), plus `shift` on the diagonal.
SparseMatrixCSC weighted_laplacian(int n, double shift) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> w(0.1, 1.0);
  std::vector<Eigen::Triplet<double>> t;
  std::vector<double> diag(n, shift);
  for (int i = 0; i + 1 < n; ++i) {
    const double a = w(rng);
    t.emplace_back(i, i + 1, -a);
    t.emplace_back(i + 1, i, -a);
    diag[i] += a;
    diag[i + 1] += a;
  }
  for (int i = 0; i < n; ++i) t.emplace_back(i, i, diag[i]);
  SparseMatrixCSC A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

}  // namespace

TEST_CASE("direct solvers: a matrix singular up to rounding is an error, not an arbitrary x") {
  const int n = 60;
  Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, 0.5, 1.5);  // sum != 0: not in the range
  for (const std::string name : {"umfpack", "sparselu"}) {
    CAPTURE(name);
    LinearSolverOptions opt;
    opt.kind = parse_linear_solver(name);
    // the nonsingular neighbour solves to rounding
    LinearSolveInfo info;
    const SparseMatrixCSC good = weighted_laplacian(n, 1e-3);
    const Eigen::VectorXd x = solve_linear(good, b, opt, &info);
    CHECK(info.relative_residual < 1e-12);
    CHECK((b - good * x).norm() / b.norm() < 1e-12);
    // the singular one: either the factorisation fails or the residual check throws; both are
    // NumericalError, and no x comes back
    bool threw = false;
    std::string what;
    try {
      solve_linear(weighted_laplacian(n, 0.0), b, opt);
    } catch (const NumericalError& e) {
      threw = true;
      what = e.what();
    }
    CHECK_MESSAGE(threw, "a singular system returned a solution");
    CHECK(!what.empty());
  }
}

TEST_CASE("fallback_note: a fall-back to the direct solver is said, with its chain and iterations; else nothing") {
  LinearSolveInfo info;
  info.solver = "gmres-2level";
  info.iterations = 12;
  CHECK(fallback_note(info).empty());
  info.solver = "gmres-2level->gmres-bilu0->umfpack";
  info.iterations = 320;
  info.fallback = true;
  const std::string s = fallback_note(info);
  CHECK(s.find("gmres-2level->gmres-bilu0->umfpack, 320 iterations") != std::string::npos);
  CHECK(s.find("--solver umfpack") != std::string::npos);
}
