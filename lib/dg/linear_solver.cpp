#include "dg/linear_solver.hpp"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseLU>
#include <Eigen/UmfPackSupport>
#include <chrono>
#include <cmath>
#include <limits>
#include <functional>
#include <memory>
#include <vector>

#include "core/error.hpp"
#include "dg/block_matrix.hpp"

namespace quadapt {

namespace {

using Eigen::VectorXd;
using Op = std::function<void(const VectorXd&, VectorXd&)>;

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// Whether the residual r = b - A x is at the rounding level of computing A x, row by row
/// (componentwise backward error, Oettli-Prager): |r_i| <= 1000 eps (|A| |x| + |b|)_i for every
/// row i. Row by row, not in norm: a few rows of large entries (the penalty of a very thin cell,
/// sigma ~ 1/h) dominate || |A| |x| ||, and a normwise test then accepted residuals far above
/// rounding everywhere else (relative residual 1.8e-4 on a mesh with one 1e-12-wide cell; an L2
/// error 6.6x a direct solve's at p = 4).
bool at_rounding_level(const Op& absA, const VectorXd& b, const VectorXd& x, const VectorXd& r) {
  if (!absA) return false;
  VectorXd t;
  absA(x, t);
  const double tol = 1000 * std::numeric_limits<double>::epsilon();
  for (Eigen::Index i = 0; i < r.size(); ++i)
    if (!(std::abs(r[i]) <= tol * (t[i] + std::abs(b[i])))) return false;
  return true;
}

/// Restarted flexible GMRES(m) (Saad 1993): right preconditioning with the preconditioned
/// vectors Z stored, so the iterate x += Z y is consistent even when the preconditioner is
/// inexact (single-precision factors); modified Gram-Schmidt, Givens rotations; the basis is
/// allocated as it grows. Returns the iterations; `res` = final true relative residual.
/// With `give_up_early`, after every restart cycle the mean reduction per iteration so far,
/// rho = (||r|| / ||b||)^(1/it), projects the iterations still needed, log(rtol) / log(rho);
/// if that exceeds max_it the solve stops there unconverged (the caller's next method is
/// cheaper than finishing: measured on stretched meshes, docs/bench-dgsolve.md).
int gmres(const Op& A, const Op& absA, const Op& Minv, const VectorXd& b, VectorXd& x, double rtol, int max_it,
          int m, double& res, bool& accepted, bool give_up_early = false) {
  const Eigen::Index n = b.size();
  const double bnorm = b.norm();
  x.setZero(n);
  accepted = true;
  if (bnorm == 0) { res = 0; return 0; }
  std::vector<VectorXd> V, Z;
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(m + 1, m);
  VectorXd cs(m), sn(m), g(m + 1), r = b, w(n);
  int it = 0;
  double beta = r.norm();
  while (it < max_it) {
    if (V.empty()) V.emplace_back(n);
    V[0] = r / beta;
    g.setZero();
    g[0] = beta;
    H.setZero();
    int j = 0;
    for (; j < m && it < max_it; ++j, ++it) {
      if (static_cast<int>(Z.size()) <= j) Z.emplace_back(n);
      Minv(V[j], Z[j]);
      A(Z[j], w);
      for (int i = 0; i <= j; ++i) {
        H(i, j) = w.dot(V[i]);
        w.noalias() -= H(i, j) * V[i];
      }
      H(j + 1, j) = w.norm();
      if (static_cast<int>(V.size()) <= j + 1) V.emplace_back(n);
      if (H(j + 1, j) > 0) V[j + 1] = w / H(j + 1, j);
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
    VectorXd y = H.topLeftCorner(j, j).triangularView<Eigen::Upper>().solve(g.head(j));
    for (int i = 0; i < j; ++i) x.noalias() += y[i] * Z[i];
    A(x, w);
    r = b - w;
    const double previous = beta;
    beta = r.norm();
    if (beta <= rtol * bnorm || beta == 0) break;
    // The Krylov estimate passed rtol but the true residual did not: accept it when it is at
    // the rounding level of A x in every row (componentwise backward error), or within 10 rtol.
    if (std::abs(g[j]) <= rtol * bnorm && at_rounding_level(absA, b, x, r)) break;
    if (beta <= 10 * rtol * bnorm && std::abs(g[j]) <= rtol * bnorm) break;
    if (beta > 0.9 * previous) break;  // stagnation: the caller judges the result
    if (give_up_early) {
      const double rho = std::pow(beta / bnorm, 1.0 / it);
      if (rho >= 1 || std::log(rtol * bnorm / beta) / std::log(rho) > max_it - it) break;
    }
  }
  res = beta / bnorm;
  accepted = beta <= 10 * rtol * bnorm || at_rounding_level(absA, b, x, r);
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
                 LinearSolverKind::BicgstabILUT, LinearSolverKind::GmresTwoLevel})
    if (linear_solver_name(k) == name) return k;
  throw InputError("unknown linear solver '" + name +
                   "' (valid: auto, umfpack, sparselu, gmres-bilu0, bicgstab-bilu0, gmres-bjacobi, bicgstab-ilut, "
                   "gmres-2level)");
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
    case LinearSolverKind::GmresTwoLevel: return "gmres-2level";
  }
  return "?";
}

namespace {

/// A direct solve is exact up to rounding (~1e-13 relative on the DG matrices measured, p <= 8);
/// above this its matrix was singular.
constexpr double kDirectResidualLimit = 1e-6;


/// One iterative attempt; returns false (x undefined) when the tolerance is not reached.
bool solve_iterative(LinearSolverKind kind, const SparseMatrixCSC& A, const BlockSparseMatrix* B,
                     const VectorXd& b, const LinearSolverOptions& opt, int max_it, VectorXd& x,
                     LinearSolveInfo& info, bool give_up_early = false) {
  auto t0 = std::chrono::steady_clock::now();
  const double bnorm = b.norm();
  double res = 0;
  int it = 0;
  bool accepted = false;
  if (kind == LinearSolverKind::BicgstabILUT) {
    Eigen::BiCGSTAB<SparseMatrixCSC, Eigen::IncompleteLUT<double>> solver;
    solver.setTolerance(opt.rtol);
    solver.setMaxIterations(max_it);
    solver.compute(A);
    info.setup_seconds += seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    x = solver.solve(b);
    it = static_cast<int>(solver.iterations());
    res = bnorm > 0 ? (b - A * x).norm() / bnorm : 0.0;
    accepted = res <= 10 * opt.rtol;
  } else {
    Op op = [&](const VectorXd& v, VectorXd& w) { B->multiply(v, w); };
    Op abs_op = [&](const VectorXd& v, VectorXd& w) { B->multiply_abs(v, w); };
    BlockILU0 ilu;
    BlockJacobi jac;
    TwoLevelPreconditioner two;
    Op pre;
    if (kind == LinearSolverKind::GmresTwoLevel) {
      if (!opt.coarse) throw NumericalError("gmres-2level needs the mesh's coarse space");
      two.compute(*B, *opt.coarse, opt.post_smooth, opt.block_order);
      info.coarse_degree = opt.coarse->degree;
      pre = [&](const VectorXd& r, VectorXd& z) { two.apply(r, z); };
    } else if (kind == LinearSolverKind::GmresBlockJacobi) {
      jac.compute(*B);
      pre = [&](const VectorXd& r, VectorXd& z) { jac.apply(r, z); };
    } else {
      ilu.compute(*B, opt.block_order);
      pre = [&](const VectorXd& r, VectorXd& z) { ilu.apply(r, z); };
    }
    info.setup_seconds += seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    if (kind == LinearSolverKind::BicgstabBlockILU) {
      it = bicgstab(op, pre, b, x, opt.rtol, max_it, res);
      accepted = res <= 10 * opt.rtol;
      if (!accepted) {
        VectorXd ax;
        op(x, ax);
        accepted = at_rounding_level(abs_op, b, x, b - ax);
      }
    } else {
      it = gmres(op, abs_op, pre, b, x, opt.rtol, max_it, opt.restart, res, accepted, give_up_early);
    }
  }
  info.solve_seconds += seconds_since(t0);
  info.iterations += std::max(it, 1);
  info.relative_residual = res;
  return accepted;
}

}  // namespace

double system_scale(double max_abs) {
  if (!(max_abs > 0) || !std::isfinite(max_abs)) return 1;
  const int e = std::ilogb(max_abs);
  if (e >= -64 && e <= 64) return 1;
  return std::ldexp(1.0, -e);
}

double scale_system(SparseMatrixCSC& A, Eigen::VectorXd& b) {
  const double s = system_scale(A.nonZeros() > 0 ? A.coeffs().cwiseAbs().maxCoeff() : 0.0);
  if (s != 1) {
    A.coeffs() *= s;
    b *= s;
  }
  return s;
}

double scale_system(BlockSparseMatrix& B, Eigen::VectorXd& b) {
  double m = 0;
  const long long n = B.num_blocks() * B.block_size() * B.block_size();
  for (long long k = 0; k < n; ++k) m = std::max(m, std::abs(B.values().data()[k]));
  const double s = system_scale(m);
  if (s != 1) {
    B.scale(s);
    b *= s;
  }
  return s;
}

bool uses_compressed_columns(LinearSolverKind kind) {
  return kind == LinearSolverKind::UmfPack || kind == LinearSolverKind::SparseLU ||
         kind == LinearSolverKind::BicgstabILUT;
}

namespace {

/// The common driver: A is given as compressed columns (csc) or blocks (blk); the other form is
/// built when a method needs it.
VectorXd solve_any(const SparseMatrixCSC* csc, const BlockSparseMatrix* blk, const VectorXd& b,
                   const LinearSolverOptions& opt, LinearSolveInfo* info_out) {
  LinearSolveInfo info;
  const double bnorm = b.norm();
  SparseMatrixCSC csc_own;
  std::unique_ptr<BlockSparseMatrix> blk_own;
  auto need_csc = [&]() -> const SparseMatrixCSC& {
    if (!csc) {
      auto t0 = std::chrono::steady_clock::now();
      csc_own = blk->to_csc();
      csc = &csc_own;
      info.setup_seconds += seconds_since(t0);
    }
    return *csc;
  };
  auto need_blk = [&]() -> const BlockSparseMatrix& {
    if (!blk) {
      auto t0 = std::chrono::steady_clock::now();
      blk_own = std::make_unique<BlockSparseMatrix>(*csc, opt.block_size);
      blk = blk_own.get();
      info.setup_seconds += seconds_since(t0);
    }
    return *blk;
  };
  auto direct = [&](LinearSolverKind kind) {
    const SparseMatrixCSC& A = need_csc();
    blk_own.reset();
    VectorXd x = kind == LinearSolverKind::SparseLU ? solve_direct_sparselu(A, b, info) : solve_direct_umfpack(A, b, info);
    info.relative_residual = bnorm > 0 ? (b - A * x).norm() / bnorm : 0.0;
    // LU of a singular matrix can "succeed" with a pivot at rounding level: the residual tells
    // (a pure-diffusion case without a Dirichlet boundary gave 0.83 and a solution 300x off)
    if (!(info.relative_residual <= kDirectResidualLimit))
      throw NumericalError(info.solver + ": relative residual " + std::to_string(info.relative_residual) +
                           " after the direct solve: the system is singular or nearly so (does the case fix u "
                           "somewhere: a Dirichlet boundary, or advection with an inflow?)");
    return x;
  };
  auto iterative = [&](LinearSolverKind kind, int max_it, VectorXd& x, bool give_up_early) {
    if (kind == LinearSolverKind::BicgstabILUT) return solve_iterative(kind, need_csc(), nullptr, b, opt, max_it, x, info);
    const BlockSparseMatrix& B = need_blk();
    return solve_iterative(kind, SparseMatrixCSC(), &B, b, opt, max_it, x, info, give_up_early);
  };
  VectorXd x;
  if (opt.kind == LinearSolverKind::UmfPack || opt.kind == LinearSolverKind::SparseLU) {
    info.solver = linear_solver_name(opt.kind);
    x = direct(opt.kind);
  } else if (opt.kind != LinearSolverKind::Auto) {
    info.solver = linear_solver_name(opt.kind);
    if (!iterative(opt.kind, opt.max_iterations, x, false))
      throw NumericalError(info.solver + " did not converge: relative residual " + std::to_string(info.relative_residual) +
                           " after " + std::to_string(info.iterations) + " iterations (try --solver umfpack)");
  } else {
    std::vector<LinearSolverKind> chain;
    if (opt.coarse && !opt.pure_advection)
      chain = {LinearSolverKind::GmresTwoLevel, LinearSolverKind::GmresBlockILU};
    else
      chain = {LinearSolverKind::GmresBlockILU};
    bool ok = false;
    for (LinearSolverKind k : chain) {
      info.solver += (info.solver.empty() ? "" : "->") + linear_solver_name(k);
      if (iterative(k, opt.auto_max_iterations, x, true)) {
        ok = true;
        break;
      }
    }
    if (!ok) {
      info.solver += "->umfpack";
      info.fallback = true;
      x = direct(LinearSolverKind::UmfPack);
    }
  }
  if (info_out) *info_out = info;
  return x;
}

}  // namespace

std::string fallback_note(const LinearSolveInfo& info) {
  if (!info.fallback) return "";
  return "the iterative solvers did not converge (" + info.solver + ", " + std::to_string(info.iterations) +
         " iterations in all); solved directly instead: for systems like this --solver umfpack alone is faster";
}

Eigen::VectorXd solve_linear(const SparseMatrixCSC& A, const Eigen::VectorXd& b, const LinearSolverOptions& opt,
                             LinearSolveInfo* info) {
  return solve_any(&A, nullptr, b, opt, info);
}

Eigen::VectorXd solve_linear(const BlockSparseMatrix& B, const Eigen::VectorXd& b, const LinearSolverOptions& opt,
                             LinearSolveInfo* info) {
  return solve_any(nullptr, &B, b, opt, info);
}

}  // namespace quadapt
