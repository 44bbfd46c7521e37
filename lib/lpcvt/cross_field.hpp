#pragma once
// Orientation of the frame where the frame leaves it free: a boundary-aligned cross field in the
// nearly isotropic cells (beyond the thesis; issue #14).
//
// The Riemannian metric 𝓜 = M^T M is unchanged by a rotation from the left, M -> R M, but the
// L_p energy (eq. 4.1) is not: |R M u|_p turns the optimal lattice (M^-1 Z^2 -> M^-1 R^T Z^2).
// Where 𝓜 is anisotropic the frame's orientation is what makes the lattice cells rectangles
// (M^-1 with orthogonal columns); where 𝓜 is isotropic, M = a Q (Q orthogonal), every
// orientation gives squares of the same size, all measured alike in the metric (angles, edge
// lengths), and the frame's angle is arbitrary (an estimator's eigenvectors of a near-isotropic
// error model are noise). A lattice at an angle to a straight wall must end its rows on it with
// about L (cos a + sin a - 1) defects (docs/quad-quality.md); aligned with the wall it needs none.
// So in those cells the lattice is turned to a cross field that is aligned with the walls and
// continuous with the anisotropic cells' orientations.
//
// Per background cell c: stretch s_c = sqrt(mu_max / mu_min) of 𝓜_c; freedom
//     w_c = 1 for s_c <= s0,  0 for s_c >= s1,  smoothstep in log s between,
// (s0 = 1.05, s1 = 1.5); the frame's lattice angle theta_c = arg(M_c^-1 e_1) and its 4-fold
// representation f_c = exp(4 i theta_c) (a cross: theta and theta + 90° are the same lattice).
// The cross field u (one complex number per cell) minimises
//     sum_{faces (i,j)} |u_i - u_j|^2 + sum_c kappa (1 - w_c)^4 |u_c - f_c|^2
//       + sum_{boundary faces e of c} |u_c - exp(4 i t_e)|^2,
// t_e the angle of the wall edge e, kappa = 100: a graph Laplacian (face neighbours) with the
// anisotropic cells and the walls as soft constraints (the fourth power leaves the nearly free
// cells unpinned: with kappa (1 - w) a cell of stretch 1.1 was held at its own angle, and the
// freedom then acted twice — in the pin and in the turn below); the normal equations are one SPD sparse
// system for the real and imaginary parts (Eigen's SimplicialLDLT). With phi_c = arg(u_c) / 4
// and d_c = phi_c - theta_c wrapped to [-45°, 45°), the cell's frame becomes
//     M_c <- R(-w_c d_c) M_c,
// so an isotropic cell's lattice is at phi_c, a partly free one turns by the fraction w_c of
// the way (a rotation in the metric: its physical cells become slightly sheared parallelograms,
// the more the larger its stretch), and an anisotropic one (w_c = 0) is untouched, bit for bit. On a constant isotropic frame of a polygon with axis-parallel walls the cross
// field is the axes (u = 1), whatever the frame's angle. A frame without a free cell (every
// s_c >= s1) is returned unchanged without a solve.
#include "lpcvt/background.hpp"

namespace quadapt::lpcvt {

struct CrossFieldReport {
  int free_cells = 0;         ///< cells with w_c > 0
  int rotated_cells = 0;      ///< cells whose M changed
  double mean_rotation_deg = 0;  ///< mean |w_c d_c| over the rotated cells, degrees
  double max_rotation_deg = 0;
};

/// Stretch limits of the freedom w_c (above).
struct CrossFieldOptions {
  double free_below = 1.05;   ///< s0: fully free at or below this stretch
  double fixed_above = 1.5;   ///< s1: the frame's orientation at or above this stretch
  double kappa = 100;         ///< weight of the anisotropic cells' own orientation (times (1 - w)^4)
};

/// The freedom w(s) of a cell of stretch s (above); s >= 1.
double orientation_freedom(double stretch, const CrossFieldOptions& o = {});

/// Turns the lattice of the nearly isotropic background cells to the boundary-aligned cross
/// field (above). 𝓜 = M^T M of every cell is unchanged (to rounding).
CrossFieldReport align_free_orientation(Background& bg, const CrossFieldOptions& o = {});

}  // namespace quadapt::lpcvt
