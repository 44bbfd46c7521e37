#pragma once
// The Gmsh interpolation scheme of quadapt's DG field (docs/design.md §3, lib/fem/basis.hpp).
//
// A degree-p DG function on a quad is stored as its (p+1)^2 nodal values at the tensor GLL
// points, index k = i + (p+1) j (i along xi, j along eta, reference square [-1,1]^2). Gmsh
// evaluates an $ElementNodeData view with an $InterpolationScheme as
//     u(xi, eta) = sum_k u_k f_k(xi, eta),   f_k = sum_m coef(k, m) xi^exp(m,0) eta^exp(m,1),
// (gmsh.h, view::setInterpolationMatrices; Gmsh's adaptiveData.cpp computeShapeFunctions:
// sf = coef * monomials), on its reference quad [-1,1]^2 with corners in the same order as ours.
// So row k of coef holds the monomial coefficients of the Lagrange basis function l_i(xi) l_j(eta):
// coef = V^-T with V(k, m) = monomial m at node k (the inverse Vandermonde, transposed).
// Monomial m = a + (p+1) b is xi^a eta^b.
#include <string>
#include <vector>

namespace quadapt {

/// Gmsh's element-family code of quadrangles in $InterpolationScheme (TYPE_QUA in GmshDefines.h).
constexpr int kGmshFamilyQuadrangle = 4;

/// "quadapt_gll_p<p>": the scheme name written as the view's second string tag.
std::string gll_scheme_name(int p);
/// The degree p encoded in such a name, or -1 when `name` is not one of ours.
int parse_gll_scheme_name(const std::string& name);

/// Interpolation matrices of the degree-p tensor GLL Lagrange basis, row-major.
struct GmshInterpolation {
  int n = 0;                 ///< (p+1)^2 basis functions = monomials
  std::vector<double> coef;  ///< n x n, coef[k*n + m]
  std::vector<double> exp;   ///< n x 3, exponents of xi, eta, (zeta = 0) of monomial m
};
GmshInterpolation gll_interpolation(int p);

}  // namespace quadapt
