#pragma once
// Curved boundary cells for a straight-sided all-quad mesh of a curved domain (docs/curved.md,
// "Curving an adapted mesh"): the mesh gets geometric order q (mesh/curved.hpp) with
//  * every boundary edge's q-1 interior control points ON the true curve, at equispaced
//    parameters between its end nodes' parameters (the end nodes are snapped first:
//    mesh/snap.hpp), so the edge interpolates the curve at q+1 points;
//  * the interior control points of the boundary cells by the transfinite (Coons) blend of the
//    cell's own edge displacements (nothing else moves); when that folds a cell, instead every
//    other control point (and every interior vertex) moved by a smooth blend of the
//    boundary edges' displacements delta_e (curve point minus chord point):
//        D(x) = sum_e phi(d_e(x) / rho_e) delta_e(s_e(x)) / max(1, sum_e phi(d_e(x) / rho_e)),
//    d_e the distance of x to the chord e, s_e in [0, 1] the projection's parameter, rho_e the
//    chord's length, delta_e(s) the degree-q interpolant of the edge's displacements and
//    phi(r) = (1 - r)^4 (4 r + 1) for r < 1 (Wendland's C2 function), 0 beyond. D is a function of
//    position only, so neighbours keep sharing their edges; |grad D| ~ sagitta / rho ~ h / (8 R)
//    (R the curve's radius of curvature) keeps thin boundary-layer cells unfolded: a cell of
//    height H next to a chord whose sagitta exceeds H is carried along instead of crushed.
// Edge nodes (BoundaryNodes): Equal puts the q-1 interior nodes at equal parameter steps (equal
// angles on a circle, as Gmsh does); the boundary integrals of the polynomial edges are then off
// by O(h^(q+1)) for odd q and O(h^(q+2)) for even q (docs/curved.md). Area (odd q >= 3): the
// interior parameters s_i = i/q are stretched symmetrically, s_i + alpha (s_i - 1/2) s_i (1 - s_i),
// with alpha (a secant solve) such that the signed area between the polynomial edge and its chord
// equals that between the curve and the chord, (1/2) int (x - a) x dx' along each. To first order
// any move of the edge nodes along the curve changes the edge's normal distance d by a multiple
// of the node polynomial omega (equispaced nodes) — one direction — and for odd q int omega != 0,
// so this kills the leading term of int d ds; what remains is O(h^(q+3)) summed over a curve
// (measured on a circle: O(h^10) at q = 3). For even q int omega = 0: Area = Equal.
// The result's minimum scaled Jacobian (mesh/curved.hpp) is reported; a cell whose sampled
// Jacobian is not positive is refused (NumericalError naming it): refine near that curve.
#include <string>

#include "mesh/geometry.hpp"
#include "mesh/mesh.hpp"
#include "mesh/snap.hpp"

namespace quadapt {

enum class BoundaryNodes { Equal, Area };

struct CurveStats {
  SnapStats snap;                 ///< the vertices' snap
  int order = 1;
  int boundary_edges = 0;         ///< boundary edges curved
  double max_sagitta = 0;         ///< largest |delta| over the boundary edges' control points
  double max_blend = 0;           ///< largest interior displacement |D|
  double max_distance = 0;        ///< boundary control points' largest distance to their curve
  double min_scaled_jacobian = 1; ///< of the result (1 for q = 1)
  int worst_cell = -1;
  int straight_edges = 0;         ///< boundary edges left straight (fallback)
  int junction_edges = 0;         ///< boundary edges across a smooth junction of two curves of one group
  std::string blend;              ///< "transfinite" (cells' own) or "smooth" (across cells)
  bool hanging = false;           ///< the mesh has 2:1 hanging nodes (transfinite blend only)
  double max_stretch = 0;         ///< BoundaryNodes::Area: largest |alpha| over the edges
};

/// Snaps m's boundary nodes to g (snap_to_geometry) and, for q >= 2, gives m geometric order q as
/// above. m: straight-sided, all quads, conforming or 2:1 non-conforming (refine's output). With
/// hanging nodes only the boundary nodes and the boundary cells' own control points move (snap
/// without interior moves, the transfinite blend only): every interior edge stays straight with
/// equispaced control points, so a coarse edge and its two halves trace the same segment with
/// the same parametrisation (dgsolve checks the traces at every face quadrature point). q in 1..kMaxGeometricOrder. With `fallback`,
/// a cell that folds either way gets its boundary edges straight (their end nodes stay on the
/// curve; counted in straight_edges) instead of the error — a sliver cell whose angle at a
/// boundary node is smaller than the arc's turn cannot take a curved edge.
CurveStats curve_boundary_cells(Mesh& m, const BoundaryGeometry& g, int q, const std::string& path,
                                bool fallback = false, BoundaryNodes nodes = BoundaryNodes::Equal);

}  // namespace quadapt
