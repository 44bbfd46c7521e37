#pragma once
// Boundary of the L_p-CVT domain: curves and their discretisation by equidistribution in the
// metric (thesis §4.2, eqs. 4.2-4.7).
//
// Curves. The background mesh's boundary edges (Mesh::boundary with its named groups; when the
// mesh has none, its free edges in one group "boundary") are chained per group and split at
// corners (turning angle above a threshold) and where groups meet. A curve is a polyline of
// background nodes; a closed loop without corners is one closed curve.
//
// Discretisation. Along a curve with arc-length parameter s, dL(s) = |M_eff(gamma(s)) tau|_q
// (tau the unit tangent; q = 2 is the thesis's eq. 4.2, the frames' default is q = p, the energy's
// exponent, as eq. 4.12 measures edges — see "Why the L_p length" below); dL is sampled at the ends of each background edge (constant per edge
// for a piecewise-constant metric; `samples_per_edge` sub-intervals in analytic mode) and taken
// piecewise linear, so L(s) = integral of dL is piecewise quadratic (eq. 4.3). The curve gets
// n = max(1, round(L_M)) segments (closed curves at least 3; the thesis uses ceil, which gives
// segments of metric length as low as 1/2 when L_M is just above an integer), and the points
// are where L(s) = i L_M / n, found by solving the quadratic of eq. 4.7 on the sub-interval.
// Curve end points (corners) are shared between curves. Boundary points are fixed afterwards.
//
// Why the L_p length (beyond the thesis; issue #14). The interior points form a lattice that is
// square in the metric, its rows along the frame's axes (M's rows: the metric coordinates). A
// wall whose metric tangent v = M tau makes an angle a with those axes is crossed by
// |v_1| + |v_2| = |v|_2 (cos a + sin a) rows of both families per unit length; every row that no
// wall point ends must end at an interior defect (a valence-3/5 pair). With the Euclidean length
// the wall gets |v|_2 points: at a = 11° (a 45° frame of stretch 5) too many for the rows of one
// family (|v|_inf = 0.98 |v|_2) and too few for both, so the rows of the dominant family end
// out of register with the points. |v|_p with p = 6 is within 0.3 % of |v|_inf for a < 25° and
// 1.12 |v|_inf at a = 45° (wall edges 1.26 instead of 1.41 lattice spacings there): one wall
// point per row of the family that crosses the wall most often. On the constant frames of
// docs/quad-quality.md it lowers the irregular vertices at 30°/60° and stretch 5 from 3.2 % to
// 2.6 % and at 15°/75°, stretch 10, from 2.5 % to 1.6 %. The lengths equal the Euclidean ones on
// walls along a lattice axis (the cross field turns the isotropic cells' lattice to the walls).
#include <array>
#include <string>
#include <vector>

#include "lpcvt/background.hpp"

namespace quadapt::lpcvt {

struct BoundaryCurve {
  int group = 0;            ///< index into the background mesh's groups
  std::vector<int> nodes;   ///< background node ids along the curve (closed: last == first)
  bool closed = false;
};

/// Chains the background boundary into curves split at corners (turn > corner_angle_deg).
/// Throws InputError if the boundary is not a set of simple chains (a node with more than two
/// boundary edges of one group is allowed only as a curve end).
std::vector<BoundaryCurve> boundary_curves(const Background& bg, double corner_angle_deg = 30);

struct BoundaryPoints {
  std::vector<Vec2> points;                 ///< boundary sites (corners once)
  std::vector<std::array<int, 2>> segments; ///< consecutive sites along the curves
  std::vector<int> segment_group;           ///< group of each segment (background group index)
  std::vector<double> curve_length;         ///< metric length L_M of each curve (eq. 4.2)
  std::vector<int> curve_segments;          ///< n of each curve
};

/// Equidistributes points along every curve (eqs. 4.2-4.7) in the metric length with the L_q
/// norm dL = |M_eff tau|_q (q = 2: eq. 4.2 itself).
BoundaryPoints mesh_boundary(const Background& bg, const std::vector<BoundaryCurve>& curves,
                             int samples_per_edge = 8, double q = 2);

/// |v|_q = (|v_1|^q + |v_2|^q)^(1/q), q >= 1 (q = 2: the Euclidean norm, bit for bit).
double lq_norm(const Vec2& v, double q);

/// Metric length of the straight segment a-b in the L_q norm, eq. 4.12:
///   integral_0^1 |M_eff(a + t (b - a)) (b - a)|_q dt,
/// by the midpoint rule on `samples` sub-intervals; samples outside the domain are skipped
/// (the mean is taken over the inside ones; returns -1 when none is inside).
double segment_metric_length(const Background& bg, const Vec2& a, const Vec2& b, double q,
                             int samples = 8);

}  // namespace quadapt::lpcvt
