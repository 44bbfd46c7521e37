#pragma once
// The L_p-CVT energy and its analytic gradient (thesis eqs. 4.1, 4.8-4.11).
//
//   E(x) = sum_i integral over (Omega_i ∩ Omega) of |M(y) (y - x_i)|_p^p dy           (4.1)
//
// with Omega_i the Euclidean Voronoi cell of site x_i, M = M_eff of the background and
// |F|_p^p = |F_0|^p + |F_1|^p. The integral is split into the pieces Omega_i ∩ Q of the
// restricted Voronoi diagram (lpcvt/rvd.hpp); each convex piece is fanned from its first vertex
// into facets (c0, c_k, c_k+1) and integrated with a triangle rule (lpcvt/quadrature.hpp;
// exact for p <= 6 even with a constant metric), eq. 4.8.
//
// Gradient, eq. 4.9: dE/dx_s = sum over facets of the direct term (the integrand depends on
// x_i; eq. 4.10 without the facet motion) plus, for every facet vertex c, (dI/dc)(dc/dx_s)
// (eq. 4.11 and the chain rule). dI/dc collects the integrand's variation with the quadrature
// points (including dM/dy for analytic metrics) and the Jacobian's. A vertex c is the
// intersection of two lines n_r . c = d_r (r = 1, 2); for the bisector of (i, j),
// g = (x_j - x_i) . c - (|x_j|^2 - |x_i|^2) / 2 = 0, so with A = [n_1; n_2],
//   dc/dx_s = -A^-1 [dg_r/dx_s],  dg/dx_i = (x_i - c)^T,  dg/dx_j = (c - x_j)^T;
// background edges are fixed lines. This covers Voronoi vertices (circumcentres, [74]) and
// clipped vertices on the boundary or on a background edge ([10]) alike. The result is the exact
// derivative of the discrete (quadrature) energy, so it matches finite differences to rounding.
//
// Parallel over integration cells (OpenMP); per-cell contributions are summed afterwards in
// cell order, so the result does not depend on the thread count.
#include <vector>

#include "lpcvt/background.hpp"
#include "lpcvt/rvd.hpp"

namespace quadapt::lpcvt {

struct EnergyResult {
  double energy = 0;
  std::vector<Vec2> grad;  ///< dE/dx_i for every site (fixed sites included); empty if not asked
  long pieces = 0;         ///< number of clipped-cell pieces integrated
};

/// E and dE/dx on the restricted Voronoi diagram `rvd` (built on the same background).
EnergyResult lp_energy(const RestrictedVoronoi& rvd, const Background& bg, double p,
                       bool gradient = true);

/// Convenience: builds the restricted Voronoi diagram of `sites` first.
EnergyResult lp_energy(const Background& bg, const std::vector<Vec2>& sites, double p,
                       bool gradient = true);

/// OpenMP is used from this many sites on (default 2000; smaller problems lose more to thread
/// start-up than they gain). Tests set 0 to exercise the parallel path.
void set_min_parallel_sites(int n);

/// Energy of one piece (tests): integral over the piece of |M (y - x_site)|_p^p.
double piece_energy(const RvdPiece& piece, const Background& bg, const Vec2& x_site, double p);

}  // namespace quadapt::lpcvt
