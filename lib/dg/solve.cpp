#include "dg/solve.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <queue>

#include "core/error.hpp"
#include "core/format.hpp"
#include "mesh/label.hpp"
#include "mesh/topology.hpp"

namespace quadapt {

namespace {
/// "" or, when the mesh's thinnest cell is under 1e-6 of its median thickness (twice the area
/// over the longest edge), a note naming it: the penalty sigma ~ 1/h of such a cell makes the
/// system numerically singular, which the solver alone blames on the boundary conditions.
std::string thin_cell_note(const Mesh& mesh) {
  const int n = mesh.num_cells();
  if (n == 0) return "";
  std::vector<double> h(n);
  for (int c = 0; c < n; ++c) {
    const Cell& cell = mesh.cells[c];
    double longest = 0;
    for (int k = 0; k < cell.nv; ++k)
      longest = std::max(longest, (mesh.nodes[cell.v[(k + 1) % cell.nv]] - mesh.nodes[cell.v[k]]).norm());
    h[c] = longest > 0 ? 2 * cell_area(mesh, c) / longest : 0;
  }
  const int thinnest = static_cast<int>(std::min_element(h.begin(), h.end()) - h.begin());
  std::vector<double> sorted = h;
  std::nth_element(sorted.begin(), sorted.begin() + n / 2, sorted.end());
  const double median = sorted[n / 2];
  if (!(h[thinnest] < 1e-6 * median)) return "";
  return "; but the mesh's " + cell_label(mesh, thinnest) + " is " + sci(h[thinnest]) + " thick against a median of " +
         sci(median) + ": a cell that thin makes the system numerically singular — remove or merge it";
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

std::vector<int> downwind_order(const Mesh& mesh, const Eigen::Vector2d& c) {
  std::vector<int> order;
  if (c.isZero(0.0)) return order;
  const int n = mesh.num_cells();
  std::vector<double> key(n);
  for (int k = 0; k < n; ++k) key[k] = c.dot(cell_centroid(mesh, k));
  order.resize(n);
  for (int k = 0; k < n; ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return key[a] < key[b]; });
  return order;
}

std::vector<int> upwind_order(const Mesh& mesh, const Eigen::Vector2d& c, const Topology* topo) {
  const std::vector<int> by_key = downwind_order(mesh, c);  // the rank: c . centroid, ties by index
  std::vector<int> order;
  if (by_key.empty()) return order;
  const int n = mesh.num_cells();
  std::vector<int> rank(n);
  for (int r = 0; r < n; ++r) rank[by_key[r]] = r;
  // the upwind graph: across each interior face with c . n != 0, upwind cell -> downwind cell
  Topology own;
  if (!topo) {
    own = build_topology(mesh);
    topo = &own;
  }
  std::vector<int> indeg(n, 0), out_ptr(n + 1, 0), out;
  auto upwind_pair = [&](const Face& f, int& up, int& down) {
    const double s = c.dot(f.normal);  // f.normal: side 0's outward normal
    if (f.is_boundary() || s == 0) return false;
    up = s > 0 ? f.cell[0] : f.cell[1];
    down = s > 0 ? f.cell[1] : f.cell[0];
    return true;
  };
  int up = -1, down = -1;
  for (const Face& f : topo->faces)
    if (upwind_pair(f, up, down)) ++out_ptr[up + 1];
  for (int k = 0; k < n; ++k) out_ptr[k + 1] += out_ptr[k];
  out.resize(out_ptr[n]);
  std::vector<int> fill(out_ptr.begin(), out_ptr.end() - 1);
  for (const Face& f : topo->faces)
    if (upwind_pair(f, up, down)) {
      out[fill[up]++] = down;
      ++indeg[down];
    }
  // Kahn's algorithm, the ready cell of least rank first: the centroid order itself wherever it
  // is already topological; a cycle (non-convex cells) is broken at its cell of least rank
  std::priority_queue<int, std::vector<int>, std::greater<int>> ready;  // ranks
  for (int k = 0; k < n; ++k)
    if (indeg[k] == 0) ready.push(rank[k]);
  std::vector<char> placed(n, 0);
  order.reserve(n);
  int scan = 0;  // by_key[< scan] are placed or queued
  while (static_cast<int>(order.size()) < n) {
    if (ready.empty()) {
      while (placed[by_key[scan]]) ++scan;
      ready.push(scan);
    }
    const int k = by_key[ready.top()];
    ready.pop();
    if (placed[k]) continue;
    placed[k] = 1;
    order.push_back(k);
    for (int e = out_ptr[k]; e < out_ptr[k + 1]; ++e)
      if (--indeg[out[e]] == 0 && !placed[out[e]]) ready.push(rank[out[e]]);
  }
  return order;
}

std::vector<int> sweep_order(const Mesh& mesh, const Eigen::Vector2d& c) {
  return downwind_order(mesh, c.isZero(0.0) ? Eigen::Vector2d(1e-3, 1.0) : c);
}

DGSolveResult dg_solve(const Mesh& mesh, const Case& cs, const DGSolveOptions& opt) {
  DGSolveResult r;
  check_case_finite(cs, mesh);
  auto t0 = std::chrono::steady_clock::now();
  DGDiscretization dg(mesh, cs, opt.p, opt.dg);
  SparseMatrixCSC A;
  BlockSparseMatrix B;
  Eigen::VectorXd b;
  const bool csc = uses_compressed_columns(opt.solver.kind);
  if (csc)
    dg.assemble(A, b);
  else
    dg.assemble(B, b);
  r.t_assemble = seconds_since(t0);

  t0 = std::chrono::steady_clock::now();
  LinearSolverOptions so = opt.solver;
  so.block_size = dg.dofs_per_cell();
  CoarseSpace coarse;  // only where gmres-2level can run
  if (needs_coarse_space(so.kind, cs.advection_only())) {
    coarse = make_coarse_space(mesh, opt.p, coarse_degree(opt.p, so.coarse_degree));
    so.coarse = &coarse;
  }
  so.pure_advection = cs.advection_only();
  // Elimination order of the block ILU: downwind along c (exact for pure upwind advection), or
  // a sweep in y when c = 0. A geometric order matters on unstructured meshes, whose file order
  // is arbitrary: 44 -> 15 iterations on examples/meshes/unstructured_square.msh.
  // Pure advection: the upwind graph's topological order, in which block ILU is the exact block
  // LU (one iteration; the centroid order is not topological on adapted meshes: docs/adjoint.md).
  if (so.block_order.empty())
    so.block_order =
        cs.advection_only() ? upwind_order(mesh, cs.advection, &dg.topology()) : sweep_order(mesh, cs.advection);
  if (csc)
    scale_system(A, b);
  else
    scale_system(B, b);
  try {
    r.U = csc ? solve_linear(A, b, so, &r.solve) : solve_linear(B, b, so, &r.solve);
  } catch (const NumericalError& e) {
    throw NumericalError(e.what() + thin_cell_note(mesh));
  }
  r.t_solve = seconds_since(t0);
  if (!r.U.allFinite()) throw NumericalError("the DG solution is not finite (singular system?)");
  A = SparseMatrixCSC();
  B = BlockSparseMatrix();

  t0 = std::chrono::steady_clock::now();
  r.p = opt.p;
  r.cells = mesh.num_cells();
  r.dofs = dg.num_dofs();
  for (const Face& f : dg.topology().faces)
    if (!f.is_boundary() && !f.is_conforming()) ++r.hanging_faces;
  r.l2_error = dg.l2_error(r.U);
  r.has_functional = dg.has_functional();
  if (r.has_functional) {
    r.functional = dg.functional(r.U);
    r.functional_exact = dg.functional_exact();
    r.functional_error = std::abs(r.functional_exact - r.functional);
  }
  r.t_postprocess = seconds_since(t0);
  return r;
}

CellNodeField make_dg_field(const Eigen::VectorXd& U, int p, int cells, const std::string& name) {
  CellNodeField f;
  f.name = name;
  f.ncomp = 1;
  f.degree = p;
  f.per_cell = (p + 1) * (p + 1);
  if (U.size() != static_cast<Eigen::Index>(f.per_cell) * cells)
    throw InputError("field '" + name + "': " + std::to_string(U.size()) + " coefficients do not match degree " +
                     std::to_string(p) + " on " + std::to_string(cells) + " cells");
  f.values.assign(U.data(), U.data() + U.size());
  return f;
}

Eigen::VectorXd dg_field_coefficients(const CellNodeField& f, int& p) {
  p = f.degree;
  if (f.ncomp != 1 || p < 1 || f.per_cell != (p + 1) * (p + 1))
    throw InputError("field '" + f.name + "' is not a scalar DG field of tensor GLL type (degree " +
                     std::to_string(f.degree) + ", " + std::to_string(f.per_cell) + " values per cell)");
  return Eigen::Map<const Eigen::VectorXd>(f.values.data(), static_cast<Eigen::Index>(f.values.size()));
}

}  // namespace quadapt
