#pragma once
// Boundary points of the L_p-CVT on the TRUE curves of a geometry (docs/curved.md, "Geometry"),
// the curved counterpart of mesh_boundary (boundary_points.hpp; thesis eqs. 4.2-4.7):
// along each curve c(t) of g, dL(t) = max(|M_eff c'(t)|_2, |c'| sqrt(16 kappa |M_eff n| / 8),
// |c'| kappa / (pi / 4)) is sampled at K equispaced
// parameters (K = max(512, 16 n)), the metric length L = integral dL dt by the trapezoidal rule,
// n = max(1, round(L)) segments (closed curves at least 3), and the points are c(t_i) with
// L(t_i) = i L / n (dL linear between samples, eq. 4.7) — exactly on the curve, equidistributed
// in the frame's metric. The second term (kappa the curvature, n the unit normal) bounds the
// sagitta kappa h^2 / 8 of a segment by 1/16 of the metric's normal spacing 1 / |M_eff n|:
// recombine's split puts a node at each segment's midpoint, which snapping to the curve moves
// by the sagitta (mesh/snap.hpp), and the thin cells of a boundary layer must not fold then.
// The third bounds each segment's tangent turn kappa h by 45 degrees, whatever the frame: the
// geometry is resolved even where the frame is coarse next to a small curved wall.
// Curve ends (the geometry's vertices) are shared sites.
//
// Where the curve leaves the background mesh (a convex boundary of a polygonal frame mesh) the
// metric of the nearest background boundary cell is used, if the curve is within a quarter of
// that cell's boundary edge from it; farther means the frame is not a mesh of g's domain.
#include <string>
#include <vector>

#include "lpcvt/background.hpp"
#include "lpcvt/boundary_points.hpp"
#include "mesh/geometry.hpp"

namespace quadapt::lpcvt {

/// The tangent turn (degrees) one boundary segment spans at most by construction: where the
/// frame asks for segments longer than R * kTargetSegmentTurnDeg (R the radius of curvature: a
/// small hole in a coarse region of the frame), the curve gets more points than the metric asks,
/// dL >= |c'| kappa / kTargetSegmentTurnDeg (in radians).
constexpr double kTargetSegmentTurnDeg = 45;
/// The largest tangent turn (degrees) one boundary segment may span: a curve with a corner inside
/// (a turn no number of points resolves) is refused.
constexpr double kMaxSegmentTurnDeg = 60;
/// A boundary segment's sagitta kappa h^2 / 8 is at most 1/kSagittaFactor of the metric's normal
/// spacing 1 / |M_eff n|: dL >= |c'| sqrt(kSagittaFactor kappa |M_eff n| / 8).
constexpr double kSagittaFactor = 16;

/// Boundary points on g's curves. `groups` receives the output mesh's boundary groups (g's
/// physical names, sorted, tags 1..n); segment_group indexes it. Throws InputError(g.source(), ...)
/// naming the curve when it lies outside the background domain, or when a segment spans a turn
/// above kMaxSegmentTurnDeg (a corner inside the curve). q: the norm of the metric length
/// dL = |M_eff c'|_q, as mesh_boundary's (boundary_points.hpp).
BoundaryPoints geometry_boundary(const Background& bg, const BoundaryGeometry& g, std::vector<BoundaryGroup>& groups,
                                 double q = 2);

}  // namespace quadapt::lpcvt
