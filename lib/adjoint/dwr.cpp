#include "adjoint/dwr.hpp"
#include "dg/degree.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>

#include "core/error.hpp"
#include "adjoint/block_sweep.hpp"
#include "adjoint/block_transpose.hpp"
#include "dg/two_level.hpp"
#include "dg/solve.hpp"

namespace quadapt {

namespace {

class Stopwatch {
 public:
  explicit Stopwatch(std::vector<std::pair<std::string, double>>& out) : out_(out) {}
  void lap(const std::string& name) {
    auto now = std::chrono::steady_clock::now();
    out_.emplace_back(name, std::chrono::duration<double>(now - t_).count());
    t_ = now;
  }

 private:
  std::vector<std::pair<std::string, double>>& out_;
  std::chrono::steady_clock::time_point t_ = std::chrono::steady_clock::now();
};

}  // namespace

Eigen::VectorXd read_solution_field(const Mesh& mesh, const std::string& field, const std::string& path, int& p) {
  const CellNodeField* f = mesh.cell_node_field(field);
  if (!f) {
    throw InputError(path, "no DG solution field '" + field + "' (expected a dgsolve output; fields present: " +
                               mesh.field_list() + ")");
  }
  Eigen::VectorXd U;
  try {
    U = dg_field_coefficients(*f, p);
  } catch (const InputError& e) {
    throw InputError(path, e.what());
  }
  const long long want = static_cast<long long>(mesh.num_cells()) * (p + 1) * (p + 1);
  if (U.size() != want)
    throw InputError(path, "field '" + field + "' has " + std::to_string(U.size()) + " values; degree " +
                               std::to_string(p) + " on " + std::to_string(mesh.num_cells()) + " cells needs " +
                               std::to_string(want));
  if (!U.allFinite()) throw InputError(path, "field '" + field + "' holds a non-finite value");
  return U;
}

Eigen::VectorXd solve_adjoint(BlockSparseMatrix A, const Eigen::VectorXd& g, const Mesh& mesh, int pf,
                              const Eigen::Vector2d& c, bool pure_advection, const AdjointOptions& opt,
                              LinearSolveInfo* info, const Topology* topo) {
  const int nb = (pf + 1) * (pf + 1);
  if (A.block_size() != nb || A.block_rows() != mesh.num_cells() || g.size() != A.rows())
    throw Error("solve_adjoint: matrix / right-hand side do not match degree " + std::to_string(pf) + " on the mesh");
  // exact (a power of two); 1 unless A's entries are far out of floating-point range (linear_solver.hpp)
  Eigen::VectorXd gs = g;
  scale_system(A, gs);
  LinearSolverOptions o = opt.solver;
  // Auto = Flow: dgsolve's geometric order with the flow reversed (lib/dg/solve.hpp sweep_order),
  // so that the block ILU does not depend on the file's cell order; with pure advection the
  // reversed flow's topological order (upwind_order of -c), in which A^T is block triangular
  if (opt.ordering != AdjointOrdering::Mesh && o.block_order.empty())
    o.block_order = pure_advection ? upwind_order(mesh, -c, topo) : sweep_order(mesh, -c);
  // Pure advection in the downstream-first order: A^T is block lower triangular, one exact
  // block sweep solves it (adjoint/block_sweep.hpp).
  if (o.kind == LinearSolverKind::Auto && pure_advection && !o.block_order.empty()) {
    auto t0 = std::chrono::steady_clock::now();
    Eigen::VectorXd x;
    double res = 0;
    if (solve_transposed_block_sweep(A, o.block_order, gs, x, &res) && res <= 10 * o.rtol) {
      if (info) {
        *info = LinearSolveInfo();
        info->solver = "block-sweep";
        info->relative_residual = res;
        info->solve_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      }
      return x;
    }
  }
  if (!transpose_in_place(A)) A = block_transpose(A);
  const BlockSparseMatrix& At = A;
  o.block_size = nb;
  o.pure_advection = pure_advection;
  CoarseSpace coarse;  // only where gmres-2level can run
  if (needs_coarse_space(o.kind, pure_advection)) {
    coarse = make_coarse_space(mesh, pf, coarse_degree(pf, o.coarse_degree));
    o.coarse = &coarse;
  }
  const LinearSolverKind kind = o.kind;
  const bool iterative = kind != LinearSolverKind::UmfPack && kind != LinearSolverKind::SparseLU &&
                         kind != LinearSolverKind::Auto;
  try {
    return solve_linear(At, gs, o, info);
  } catch (const NumericalError&) {
    if (!iterative || !opt.fallback_direct) throw;
    o.kind = LinearSolverKind::UmfPack;
    Eigen::VectorXd x = solve_linear(At, gs, o, info);
    if (info) {
      info->solver = linear_solver_name(kind) + "->umfpack";
      info->fallback = true;
    }
    return x;
  }
}

DGOptions fine_dg_options(const DGOptions& primal, int p) {
  DGOptions o = primal;
  // Dirichlet faces keep the fine space's own penalty: there the term (sigma_fine - sigma_H)
  // (u_H - g) psi has no neighbour to cancel against and keeps the weak boundary mismatch (what a
  // functional on a Dirichlet boundary measures) in the indicators — a heuristic proportion
  if (o.boundary_penalty_factor < 0) o.boundary_penalty_factor = primal.penalty_factor;
  o.penalty_factor = primal.penalty_factor * p / (p + 2);  // interior faces: factor' (p+1)(p+2) = factor p(p+1)
  return o;
}

DWRResult compute_dwr(const Mesh& mesh, const Case& cs, const Eigen::VectorXd& U, int p, const AdjointOptions& opt) {
  if (!cs.has_functional())
    throw InputError(cs.path, "the case has no functional; add \"functional\": {\"boundary\": NAME} "
                              "(J = integral of u^2 over that boundary)");
  check_case_boundaries(cs, mesh);
  check_case_finite(cs, mesh);
  const int nc = mesh.num_cells();
  // the fine space has degree p + 1, which the DG library must support
  check_degree(p, "the solution's degree p =", kMaxAdjointDegree);
  const long long nbc = static_cast<long long>(p + 1) * (p + 1);
  if (U.size() != nbc * nc)
    throw InputError("adjoint: solution vector of size " + std::to_string(U.size()) + " does not match degree " +
                     std::to_string(p) + " on " + std::to_string(nc) + " cells");

  DWRResult r;
  r.p = p;
  r.p_fine = p + 1;
  r.dofs = nbc * nc;
  Stopwatch sw(r.timings);

  DGDiscretization fine(mesh, cs, p + 1, fine_dg_options(opt.dg, p));
  const int nb = fine.dofs_per_cell();
  r.fine_dofs = fine.num_dofs();
  sw.lap("fine_setup");

  const Eigen::VectorXd Uh = fine.inject(U, p);
  sw.lap("inject");

  BlockSparseMatrix A;
  Eigen::VectorXd b;
  fine.assemble(A, b);
  sw.lap("fine_assemble");

  A.multiply(Uh, r.residual);
  r.residual -= b;
  const Eigen::VectorXd g = fine.functional_gradient(Uh);
  r.functional = fine.functional(Uh);
  r.functional_exact = fine.functional_exact();
  r.functional_error = r.functional_exact - r.functional;
  sw.lap("residual_and_gradient");

  r.psi = solve_adjoint(std::move(A), g, mesh, p + 1, cs.advection, cs.advection_only(), opt, &r.solve,
                        &fine.topology());
  sw.lap("adjoint_solve");

  r.eta.resize(nc);
  r.eta_signed.resize(nc);
  double est = 0, sum = 0;
  for (int k = 0; k < nc; ++k) {
    const long long o = static_cast<long long>(k) * nb;
    const double s = -r.psi.segment(o, nb).dot(r.residual.segment(o, nb));
    r.eta_signed[k] = s;
    r.eta[k] = std::abs(s);
    est += s;
    sum += std::abs(s);
  }
  r.estimate = est;
  r.sum_eta = sum;
  r.effectivity = r.functional_error != 0 ? r.estimate / r.functional_error
                                          : std::numeric_limits<double>::quiet_NaN();
  r.corrected = r.functional + r.estimate;
  sw.lap("dwr");
  return r;
}

nlohmann::json to_json(const DWRResult& r) {
  auto num = [](double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); };
  nlohmann::json j;
  j["p"] = r.p;
  j["p_fine"] = r.p_fine;
  j["dofs"] = r.dofs;
  j["fine_dofs"] = r.fine_dofs;
  j["functional"] = r.functional;
  j["functional_exact"] = r.functional_exact;
  j["functional_error"] = std::abs(r.functional_error);
  j["functional_error_signed"] = r.functional_error;
  j["functional_error_estimate"] = r.estimate;
  j["sum_eta"] = r.sum_eta;
  j["effectivity"] = num(r.effectivity);
  j["functional_corrected"] = r.corrected;
  j["functional_corrected_error"] = std::abs(r.functional_exact - r.corrected);
  j["eta_max"] = r.eta.empty() ? 0.0 : *std::max_element(r.eta.begin(), r.eta.end());
  j["residual_norm"] = r.residual.norm();
  j["solver"] = r.solve.solver;
  j["solver_iterations"] = r.solve.iterations;
  j["solver_relative_residual"] = r.solve.relative_residual;
  j["solver_coarse_degree"] = r.solve.coarse_degree;
  j["solver_fallback"] = r.solve.fallback;
  j["solver_setup_s"] = r.solve.setup_seconds;
  j["solver_solve_s"] = r.solve.solve_seconds;
  for (const auto& [name, t] : r.timings) j["timings"][name] = t;
  return j;
}

void add_dwr_fields(Mesh& mesh, const DWRResult& r) {
  CellField dwr;
  dwr.name = "dwr";
  dwr.ncomp = 1;
  dwr.values = r.eta;
  mesh.set_field(std::move(dwr));
  mesh.set_field(make_dg_field(r.psi, r.p_fine, mesh.num_cells(), "psi"));
}

}  // namespace quadapt
