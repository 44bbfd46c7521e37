#pragma once
// Patchwise H1 reconstruction of a degree-(p+1) polynomial from a DG field (thesis eq. 5.8).
//
// For cell k with patch D(k) = {k} ∪ face neighbours (conforming or hanging-node, from
// mesh/topology.hpp), the enriched polynomial ũ ∈ P^n(D(k)) (total degree n, normally n = p+1)
// solves
//     <ũ, φ>_{H1(D(k))} = <u_h, φ>_{H1(D(k))}   for all φ ∈ P^n(D(k)),
// with the broken H1 inner product <u,v> = Σ_cells ∫ (u v + L² ∇u·∇v) dx, L = domain_length(mesh),
// the power of two nearest to sqrt(domain area). L makes the fit nearly independent of the unit
// of length (exactly for scalings by powers of two; within the effect of a factor sqrt 2 in L
// otherwise — metres to millimetres is 1000 = 0.98 x 2^10), and it is rotation invariant. On the
// unit square and the L-shape (area 1, 0.75) L = 1: the thesis's / PHiLiP's physical H1
// product, to the bit. With L = 1 on every domain the value and gradient terms traded places as
// the domain grew (on [0, 2s] x [0, s], s = 0.01 ... 100: A1 s^3 356.8, 357.3, 389.1, 528.6 at
// s = 0.01, 1, 10, 100; docs/estimate-frame.md). (A bounding box's side would not do: it
// changes when the domain turns.)
// Integrals use an (n+1)-point Gauss–Legendre tensor
// rule per patch cell (exact for the mass term on parallelograms). Because ũ is a projection,
// any u_h that is itself in P^n on the patch is reproduced exactly (to rounding), whatever the
// quadrature — the unit tests rely on this.
//
// The polynomial is represented by monomials in scaled local coordinates
//     s = (x - x_c) / H,  t = (y - y_c) / H,
// x_c = centroid of cell k, H = largest distance from x_c to a patch vertex (so |s|,|t| <= 1
// and the normal matrix is well conditioned).
#include <Eigen/Core>
#include <utility>
#include <vector>

#include "fem/basis.hpp"
#include "mesh/mesh.hpp"

namespace quadapt {

/// Total-degree-n monomial exponents (i, j) for s^i t^j, ordered by total degree, then by
/// decreasing i: (0,0), (1,0),(0,1), (2,0),(1,1),(0,2), ... Size (n+1)(n+2)/2.
std::vector<std::pair<int, int>> monomial_exponents(int n);

/// The length unit of the reconstruction's H1 product: the power of two nearest to sqrt of the
/// mesh's area (sum of |cell area|, straight cells), 1 for an empty or degenerate mesh.
double domain_length(const Mesh& mesh);

/// A polynomial of total degree n in scaled local coordinates about `center`.
struct PatchPolynomial {
  int degree = 0;
  Vec2 center{0, 0};
  double scale = 1;             ///< H (physical length)
  Eigen::VectorXd coeffs;       ///< one per monomial_exponents(degree) entry

  /// ũ(x) at a physical point.
  double eval(const Vec2& x) const;
  /// Coefficients a_i (i = 0..n) of the top-degree homogeneous part in PHYSICAL units:
  /// ũ(x_c + y) = ... + Σ_i a_i y_x^i y_y^(n-i). Equals D^n ũ[ξ,...,ξ]/n! when evaluated at a
  /// unit vector ξ (the Taylor term of eqs. 5.6-5.7). Translation invariant.
  std::vector<double> top_homogeneous() const;
};

/// Reconstructs degree-n patch polynomials from a DG field of degree p on straight bilinear
/// quads (the "u" CellNodeField: (p+1)^2 GLL-node values per cell, index i + (p+1) j).
class PatchReconstructor {
 public:
  /// `values`: the DG coefficients, mesh.num_cells() * (p+1)^2 (cell-major). Requires an
  /// all-quad mesh (throws InputError otherwise). n >= 1. Keeps a reference to `mesh` only.
  PatchReconstructor(const Mesh& mesh, const std::vector<double>& values, int p, int n);

  /// ũ on the patch `patch` (cell indices; must contain `cell`), centred on `cell`.
  /// Throws NumericalError if the normal matrix is singular (cannot happen for cells of
  /// positive area).
  PatchPolynomial reconstruct(int cell, const std::vector<int>& patch) const;

  int field_degree() const { return p_; }
  int degree() const { return n_; }

 private:
  const Mesh& mesh_;
  int p_, n_;
  Rule1D rule_;
  std::vector<std::pair<int, int>> exps_;
  int nq_ = 0;                 ///< quadrature points per cell, (n+1)^2
  double length_ = 1;          ///< L of the H1 product (domain_length)
  /// Per cell and quadrature point: x, y, sqrt(w |J|), u, du/dx, du/dy (precomputed once).
  std::vector<double> qdata_;
};

}  // namespace quadapt
