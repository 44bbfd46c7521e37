#pragma once
// One DG solve, end to end (what the dgsolve tool runs): discretise, assemble, solve, and
// post-process (L2 error against the exact solution, functional J(u_h), J(u_exact)).
// Also the conversion between a coefficient vector and the mesh field "u".
#include <Eigen/Core>
#include <string>
#include <vector>

#include "case/case.hpp"
#include "dg/discretization.hpp"
#include "dg/linear_solver.hpp"
#include "mesh/mesh.hpp"

namespace quadapt {

struct DGSolveOptions {
  int p = 1;                   ///< polynomial degree (1..8)
  DGOptions dg;                ///< penalty factor, quadrature
  LinearSolverOptions solver;  ///< block_size is set from p
};

struct DGSolveResult {
  int p = 0;
  int cells = 0;
  int dofs = 0;
  int hanging_faces = 0;           ///< non-conforming (2:1) faces of the mesh
  Eigen::VectorXd U;               ///< coefficients, dof = cell (p+1)^2 + i + (p+1) j
  double l2_error = 0;             ///< ||u_h - u_exact||_L2
  bool has_functional = false;
  double functional = 0;           ///< J(u_h) = int over the case's boundary of u_h^2
  double functional_exact = 0;     ///< J(u_exact)
  double functional_error = 0;     ///< |J(u_exact) - J(u_h)|
  LinearSolveInfo solve;
  double t_assemble = 0, t_solve = 0, t_postprocess = 0;  ///< wall seconds
};

/// Cells sorted along the advection direction c (c . centroid, ties by index): a geometric
/// elimination order for block ILU. Empty when c = 0.
std::vector<int> downwind_order(const Mesh& mesh, const Eigen::Vector2d& c);

/// The cells upwind first along the constant advection c: a topological order of the upwind
/// graph (across each interior face with c . n != 0, the cell the flow leaves comes first), the
/// cell of least c . centroid (ties by index) taken first among those ready (Kahn's algorithm) —
/// so it is the centroid order wherever that is already topological (structured grids), and
/// where it is not (stretched cells staggered along their long axis: a quarter of the faces of
/// an adapted S-shock mesh) it is the order in which the upwind DG matrix is block triangular
/// and block ILU exact. A cycle (possible only with non-convex cells; convex cells in 2-D always
/// have a topological order along a constant direction) is broken at its cell of least
/// c . centroid. Empty when c = 0. `topo`: the mesh's faces when the caller has them (a
/// DGDiscretization's), else they are built here (build_topology is a large part of a
/// pure-advection dgsolve).
std::vector<int> upwind_order(const Mesh& mesh, const Eigen::Vector2d& c, const Topology* topo = nullptr);

/// The block ILU's elimination order of dgsolve and adjoint: downwind_order along c, or a sweep
/// in y when c = 0 (a geometric order: the file's cell order of an adapted mesh is arbitrary).
std::vector<int> sweep_order(const Mesh& mesh, const Eigen::Vector2d& c);

/// Solves the case on the mesh. Throws InputError (bad mesh / degree / boundary names) or
/// NumericalError (singular system).
DGSolveResult dg_solve(const Mesh& mesh, const Case& cs, const DGSolveOptions& opt);

/// The CellNodeField `name` holding U as a degree-p DG field ((p+1)^2 values per cell).
CellNodeField make_dg_field(const Eigen::VectorXd& U, int p, int cells, const std::string& name = "u");

/// The coefficients of a DG CellNodeField and its degree. Throws InputError when the field is
/// not a scalar tensor-GLL field ((p+1)^2 values per cell, degree p >= 1).
Eigen::VectorXd dg_field_coefficients(const CellNodeField& f, int& p);

}  // namespace quadapt
