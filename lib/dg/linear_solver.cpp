#include "dg/linear_solver.hpp"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseLU>
#include <Eigen/UmfPackSupport>
#include <chrono>
#include <cmath>
#include <functional>

#include "core/error.hpp"
#include "dg/block_matrix.hpp"

namespace quadapt {

namespace {

using Eigen::VectorXd;
using Op = std::function<void(const VectorXd&, VectorXd&)>;

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// Restarted GMRES(m), right preconditioning (x = M^-1 y), modified Gram-Schmidt with Givens
/// rotations. Returns iterations; `res` = final true relative residual.
int gmres(const Op& A, const Op& Minv, const VectorXd& b, VectorXd& x, double rtol, int max_it, int m,
          double& res) {
  const Eigen::Index n = b.size();
  const double bnorm = b.norm();
  x.setZero(n);
  if (bnorm == 0) { res = 0; return 0; }
  Eigen::MatrixXd V(n, m + 1), H = Eigen::MatrixXd::Zero(m + 1, m);
  VectorXd cs(m), sn(m), g(m + 1), r(n), w(n), z(n);
  int it = 0;
  r = b;  // x = 0
  double beta = r.norm();
  while (it < max_it) {
    V.col(0) = r / beta;
    g.setZero();
    g[0] = beta;
    H.setZero();
    int j = 0;
    for (; j < m && it < max_it; ++j, ++it) {
      Minv(V.col(j), z);
      A(z, w);
      for (int i = 0; i <= j; ++i) {
        H(i, j) = w.dot(V.col(i));
        w.noalias() -= H(i, j) * V.col(i);
      }
      H(j + 1, j) = w.norm();
      if (H(j + 1, j) > 0) V.col(j + 1) = w / H(j + 1, j);
      for (int i = 0; i < j; ++i) {
        double t = cs[i] * H(i, j) + sn[i] * H(i + 1, j);
        H(i + 1, j) = -sn[i] * H(i, j) + cs[i] * H(i + 1, j);
        H(i, j) = t;
      }
      double d = std::hypot(H(j, j), H(j + 1, j));
      cs[j] = d > 0 ? H(j, j) / d : 1;
      sn[j] = d > 0 ? H(j + 1, j) / d : 0;
      H(j, j) = d;
      H(j + 1, j) = 0;
      g[j + 1] = -sn[j] * g[j];
      g[j] = cs[j] * g[j];
      if (std::abs(g[j + 1]) <= rtol * bnorm) { ++j; ++it; break; }
    }
    // y = H^-1 g (upper triangular j x j); x += M^-1 V y.
    VectorXd y = H.topLeftCorner(j, j).triangularView<Eigen::Upper>().solve(g.head(j));
    VectorXd vy = V.leftCols(j) * y;
    Minv(vy, z);
    x += z;
    A(x, w);
    r = b - w;
    beta = r.norm();
    if (beta <= rtol * bnorm || beta == 0) break;
  }
  res = beta / bnorm;
  return it;
}

/// Right-preconditioned BiCGSTAB.
int bicgstab(const Op& A, const Op& Minv, const VectorXd& b, VectorXd& x, double rtol, int max_it, double& res) {
  const Eigen::Index n = b.size();
  const double bnorm = b.norm();
  x.setZero(n);
  if (bnorm == 0) { res = 0; return 0; }
  VectorXd r = b, r0 = b, p = VectorXd::Zero(n), v = VectorXd::Zero(n), s(n), t(n), ph(n), sh(n);
  double rho = 1, alpha = 1, omega = 1;
  int it = 0;
  for (; it < max_it; ++it) {
    double rho1 = r0.dot(r);
    if (rho1 == 0) break;
    double beta = (rho1 / rho) * (alpha / omega);
    p = r + beta * (p - omega * v);
    Minv(p, ph);
    A(ph, v);
    alpha = rho1 / r0.dot(v);
    s = r - alpha * v;
    if (s.norm() <= rtol * bnorm) {
      x += alpha * ph;
      ++it;
      break;
    }
    Minv(s, sh);
    A(sh, t);
    omega = t.dot(s) / t.dot(t);
    x += alpha * ph + omega * sh;
    r = s - omega * t;
    rho = rho1;
    if (r.norm() <= rtol * bnorm) { ++it; break; }
    if (omega == 0) break;
  }
  VectorXd w(n);
  A(x, w);
  res = (b - w).norm() / bnorm;
  return it;
}

VectorXd solve_direct_umfpack(const SparseMatrixCSC& A, const VectorXd& b, LinearSolveInfo& info) {
  auto t0 = std::chrono::steady_clock::now();
  Eigen::UmfPackLU<SparseMatrixCSC> lu;
  lu.compute(A);
  if (lu.info() != Eigen::Success) throw NumericalError("UMFPACK could not factorise the DG matrix (singular?)");
  info.setup_seconds += seconds_since(t0);
  t0 = std::chrono::steady_clock::now();
  VectorXd x = lu.solve(b);
  info.solve_seconds += seconds_since(t0);
  return x;
}

VectorXd solve_direct_sparselu(const SparseMatrixCSC& A, const VectorXd& b, LinearSolveInfo& info) {
  auto t0 = std::chrono::steady_clock::now();
  Eigen::SparseLU<SparseMatrixCSC, Eigen::COLAMDOrdering<int>> lu;
  lu.compute(A);
  if (lu.info() != Eigen::Success) throw NumericalError("SparseLU could not factorise the DG matrix: " + lu.lastErrorMessage());
  info.setup_seconds += seconds_since(t0);
  t0 = std::chrono::steady_clock::now();
  VectorXd x = lu.solve(b);
  info.solve_seconds += seconds_since(t0);
  return x;
}

}  // namespace

LinearSolverKind parse_linear_solver(const std::string& name) {
  for (auto k : {LinearSolverKind::Auto, LinearSolverKind::UmfPack, LinearSolverKind::SparseLU,
                 LinearSolverKind::GmresBlockILU, LinearSolverKind::BicgstabBlockILU, LinearSolverKind::GmresBlockJacobi,
                 LinearSolverKind::BicgstabILUT})
    if (linear_solver_name(k) == name) return k;
  throw InputError("unknown linear solver '" + name +
                   "' (valid: auto, umfpack, sparselu, gmres-bilu0, bicgstab-bilu0, gmres-bjacobi, bicgstab-ilut)");
}

std::string linear_solver_name(LinearSolverKind kind) {
  switch (kind) {
    case LinearSolverKind::Auto: return "auto";
    case LinearSolverKind::UmfPack: return "umfpack";
    case LinearSolverKind::SparseLU: return "sparselu";
    case LinearSolverKind::GmresBlockILU: return "gmres-bilu0";
    case LinearSolverKind::BicgstabBlockILU: return "bicgstab-bilu0";
    case LinearSolverKind::GmresBlockJacobi: return "gmres-bjacobi";
    case LinearSolverKind::BicgstabILUT: return "bicgstab-ilut";
  }
  return "?";
}

Eigen::VectorXd solve_linear(const SparseMatrixCSC& A, const Eigen::VectorXd& b, const LinearSolverOptions& opt,
                             LinearSolveInfo* info_out) {
  LinearSolveInfo info;
  LinearSolverKind kind = opt.kind == LinearSolverKind::Auto ? LinearSolverKind::UmfPack : opt.kind;
  info.solver = linear_solver_name(kind);
  VectorXd x;
  const double bnorm = b.norm();
  auto finish = [&](VectorXd&& sol) {
    if (info.iterations == 0) info.relative_residual = bnorm > 0 ? (b - A * sol).norm() / bnorm : 0.0;
    if (info_out) *info_out = info;
    return std::move(sol);
  };
  if (kind == LinearSolverKind::UmfPack) return finish(solve_direct_umfpack(A, b, info));
  if (kind == LinearSolverKind::SparseLU) return finish(solve_direct_sparselu(A, b, info));

  auto t0 = std::chrono::steady_clock::now();
  double res = 0;
  int it = 0;
  if (kind == LinearSolverKind::BicgstabILUT) {
    Eigen::BiCGSTAB<SparseMatrixCSC, Eigen::IncompleteLUT<double>> solver;
    solver.setTolerance(opt.rtol);
    solver.setMaxIterations(opt.max_iterations);
    solver.compute(A);
    info.setup_seconds = seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    x = solver.solve(b);
    it = static_cast<int>(solver.iterations());
    res = bnorm > 0 ? (b - A * x).norm() / bnorm : 0.0;
  } else {
    BlockSparseMatrix B(A, opt.block_size);
    Op op = [&](const VectorXd& v, VectorXd& w) { B.multiply(v, w); };
    BlockILU0 ilu;
    BlockJacobi jac;
    Op pre;
    if (kind == LinearSolverKind::GmresBlockJacobi) {
      jac.compute(B);
      pre = [&](const VectorXd& r, VectorXd& z) { jac.apply(r, z); };
    } else {
      ilu.compute(B);
      pre = [&](const VectorXd& r, VectorXd& z) { ilu.apply(r, z); };
    }
    info.setup_seconds = seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    if (kind == LinearSolverKind::BicgstabBlockILU)
      it = bicgstab(op, pre, b, x, opt.rtol, opt.max_iterations, res);
    else
      it = gmres(op, pre, b, x, opt.rtol, opt.max_iterations, opt.restart, res);
  }
  info.solve_seconds = seconds_since(t0);
  info.iterations = std::max(it, 1);
  info.relative_residual = res;
  // Accept a residual a little above the tolerance (rounding in the true residual).
  if (!(res <= 10 * opt.rtol)) {
    if (opt.kind == LinearSolverKind::Auto) {
      LinearSolveInfo d;
      VectorXd xd = solve_direct_umfpack(A, b, d);
      d.solver = info.solver + "->umfpack";
      d.iterations = 0;
      d.fallback = true;
      d.setup_seconds += info.setup_seconds;
      d.solve_seconds += info.solve_seconds;
      info = d;
      return finish(std::move(xd));
    }
    throw NumericalError(info.solver + " did not converge: relative residual " + std::to_string(res) + " after " +
                         std::to_string(it) + " iterations (try --solver umfpack)");
  }
  return finish(std::move(x));
}

}  // namespace quadapt
