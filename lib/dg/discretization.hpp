#pragma once
// The DG discretisation of steady advection-diffusion on all-quad meshes, conforming or with
// 2:1 hanging nodes (thesis section 2.1, eq. 2.9; PDE eq. 6.2; docs/design.md §4).
//
// PDE (thesis sign convention, eq. 6.2):  div(D grad u) - c . grad u = S.  We discretise the
// equivalent well-posed form  -div(D grad u) + c . grad u = f  with  f = -S.
//
// Space: on every cell K the tensor-product Lagrange polynomials of degree p on Gauss-Lobatto
// points (fem/basis.hpp), mapped by the bilinear map of the straight-sided quad. Global dof
// numbering: dof = K * (p+1)^2 + i + (p+1) j, i.e. the coefficients are the nodal values at the
// GLL points (xi_i, eta_j) of cell K — exactly the layout of the CellNodeField "u".
//
// Weak form (eq. 2.9 with the fluxes below): find u_h with a(u_h, v) = l(v) for all v, where
//   a(u, v) = sum_K  int_K ( D grad u . grad v  -  u c . grad v )
//           + sum_F  int_F (c.n) u^up [v]                                   (upwind advection)
//           - sum_F  int_F ( {D grad u}.n [v] + {D grad v}.n [u] - sigma [u][v] )   (SIPG)
//   l(v)    = int f v + Dirichlet data terms (below),
// over interior faces F with unit normal n (from side 0 to side 1), [w] = w_0 - w_1,
// {q} = (q_0 + q_1)/2, u^up the trace on the side c.n points away from, and penalty
//   sigma = penalty_factor * p (p+1) * (n^T D n) / h_F,   h_F = min over the two sides of
//   |K| / |edge of K|  (the cell's height normal to the face; PHiLiP's factor 20 by default).
// Boundary faces:
//   Dirichlet (the case names the boundary): the outside state is g = the case's data
//     expression for that boundary, else u_exact, i.e.
//     int (c.n) (u if c.n >= 0 else g) v  -  int (D grad u.n v + D grad v.n (u - g))
//     + int sigma (u - g) v;  with D = 0 only the inflow data (c.n < 0) acts.
//   Natural (not named): the diffusive flux is given (the case's "neumann" expression, else
//     D grad u_exact . n) and the
//     advective flux is upwind with the outside state u_exact (interior trace on outflow).
// Quadrature: Gauss with p+2 points per direction in cells and on faces (faces are integrated
// in physical arc length and mapped into each side's reference coordinates, so non-conforming
// faces are exact for polynomial traces).
//
// Curved quads (mesh/curved.hpp): the bilinear map is replaced by the cell's Lagrange map of
// geometric order q (isoparametric when q = p, sub-/super-parametric otherwise; conforming
// curved meshes only); on their faces the normal, the arc length and the data points vary
// along the face (side 0's map).
//
// The linear system is A U = b; the residual is R(U) = A U - b and the Jacobian dR/dU = A. The
// assembly is column-oriented: every cell computes its own block column (its volume block and
// the face blocks where its basis functions are the trial functions) with OpenMP, writing the
// compressed column storage directly; the result does not depend on the number of threads.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>
#include <memory>
#include <vector>

#include "case/case.hpp"
#include "fem/basis.hpp"
#include "dg/block_matrix.hpp"
#include "mesh/mesh.hpp"
#include "mesh/topology.hpp"

namespace quadapt {

using SparseMatrixCSC = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

struct DGOptions {
  double penalty_factor = 20.0;  ///< SIPG sigma = factor * p(p+1) * n^T D n / h
  /// The factor on Dirichlet boundary faces; < 0 (the default): penalty_factor. The adjoint's fine
  /// space sets the two apart (adjoint/dwr.hpp, fine_dg_options).
  double boundary_penalty_factor = -1.0;
  int extra_points = 1;          ///< Gauss points per direction = p + 1 + extra_points (>= 1)
  int error_points = 0;          ///< points per direction for l2_error; 0 = max(2p + 4, 10)
};

class DGDiscretization {
 public:
  /// Builds the discretisation of `cs` on `mesh` (all quads, counter-clockwise) with degree
  /// p in [1, 8]. Keeps references to mesh and cs: they must outlive this object. Throws
  /// InputError for triangles, p out of range, options outside their stated ranges (DGOptions)
  /// or a boundary face without a group while the case names Dirichlet boundaries.
  DGDiscretization(const Mesh& mesh, const Case& cs, int p, const DGOptions& opt = {});
  ~DGDiscretization();
  DGDiscretization(const DGDiscretization&) = delete;
  DGDiscretization& operator=(const DGDiscretization&) = delete;

  int degree() const { return p_; }
  int dofs_per_cell() const { return nb_; }
  int num_cells() const { return mesh_.num_cells(); }
  /// cells * (p+1)^2 (thesis eq. 2.10 with 2.5).
  int num_dofs() const { return nb_ * mesh_.num_cells(); }
  const Mesh& mesh() const { return mesh_; }
  const Case& problem() const { return cs_; }
  const Topology& topology() const { return topo_; }
  const ExactSolution& exact() const { return *exact_; }

  /// Assembles A (num_dofs square, compressed column storage, block pattern: a cell's block
  /// column holds rows of itself and its face neighbours) and b.
  void assemble(SparseMatrixCSC& A, Eigen::VectorXd& b) const;
  /// Same system in block form (block = cell), as the block preconditioners use it: no
  /// compressed-column copy is made.
  void assemble(BlockSparseMatrix& A, Eigen::VectorXd& b) const;
  /// R(U) = A U - b (assembles).
  Eigen::VectorXd residual(const Eigen::VectorXd& U) const;

  /// || u_h - u_exact ||_{L2} with a Gauss rule of DGOptions::error_points per direction.
  double l2_error(const Eigen::VectorXd& U) const;
  /// Per-cell squared L2 errors (same quadrature).
  std::vector<double> cell_l2_errors_squared(const Eigen::VectorXd& U) const;

  /// Whether the case has a functional (J = integral of u^2 over the named boundary).
  bool has_functional() const { return has_functional_; }
  /// J(u_h) = int_Gamma u_h^2 ds over the case's functional boundary (exact for the polynomial).
  double functional(const Eigen::VectorXd& U) const;
  /// dJ/dU (num_dofs): entries int_Gamma 2 u_h phi_a ds.
  Eigen::VectorXd functional_gradient(const Eigen::VectorXd& U) const;
  /// J(u_exact) by composite Gauss quadrature along the boundary faces (accurate to rounding
  /// for smooth data).
  double functional_exact() const;

  /// Nodal interpolant of the exact solution (values at the mapped GLL points).
  Eigen::VectorXd interpolate_exact() const;
  /// Re-expresses a degree-p_from DG vector on the same mesh in this degree's basis (exact
  /// injection when p_from <= p; nodal interpolation otherwise).
  Eigen::VectorXd inject(const Eigen::VectorXd& U_from, int p_from) const;
  /// Value of u_h in cell c at reference point (xi, eta).
  double evaluate(const Eigen::VectorXd& U, int c, double xi, double eta) const;

 private:
  struct Impl;
  /// The assembly loop; scatter(c, blocks) stores cell c's block column (blocks[k] is the
  /// block of row cell rows(c)[k]), called concurrently for different c.
  void assemble_columns(const std::function<void(int, const std::vector<Eigen::MatrixXd>&)>& scatter,
                        Eigen::VectorXd& b) const;
  const Mesh& mesh_;
  const Case& cs_;
  int p_, nb_;
  DGOptions opt_;
  Topology topo_;
  std::unique_ptr<ExactSolution> exact_;
  std::unique_ptr<Impl> impl_;
  bool has_functional_ = false;
  std::vector<char> functional_groups_;  ///< per mesh group: named as the functional's boundary
  bool on_functional_boundary(const Face& f) const {
    return f.is_boundary() && f.group >= 0 && functional_groups_[f.group];
  }
  std::vector<char> face_dirichlet_;  ///< per face (boundary faces): Dirichlet data?
};

}  // namespace quadapt
