#pragma once
// The frame written for the mesh generators (thesis eqs. 3.11-3.13, docs/design.md §3).
//
// V = R(θ) diag(h1, h2), h1 = h sqrt(ρ), h2 = h / sqrt(ρ): columns v (long axis, along θ) and w.
// The target element spans ±v, ±w (edges 2h1 x 2h2, density d = 1/(4h^2), eq. 5.1).
// M = V^-1 = diag(1/h1, 1/h2) R(-θ) (eq. 3.13); the Riemannian metric for BAMG is M^T M.
// "Vinv" is stored as 9 components, row-major 3x3, zero-padded, M in the upper-left 2x2 —
// the layout PHiLiP writes. NOTE on scale: PHiLiP's own files use full-edge lengths
// (∫ det M = number of final quads), i.e. M_PHiLiP = M / 2 for the same target mesh.
#include <Eigen/Core>
#include <array>

#include "mesh/mesh.hpp"
#include "sizing/size_field.hpp"

namespace quadapt {

/// M = diag(1/h1, 1/h2) R(-θ) for h = sqrt(h1 h2), ρ = h1/h2.
Eigen::Matrix2d frame_inverse(double h, double rho, double theta);

/// The 9 row-major components of the zero-padded 3x3 with M in the upper-left 2x2.
std::array<double, 9> vinv_components(const Eigen::Matrix2d& M);

/// FRAME mesh: shape's geometry and boundary groups, no input fields, plus CellFields
/// "Vinv" (9 comps), "h", "theta", "rho" (and "alpha" in goal mode).
Mesh make_frame_mesh(const Mesh& shape, const SizeResult& r);

}  // namespace quadapt
