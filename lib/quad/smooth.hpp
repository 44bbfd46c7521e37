#pragma once
// Angle-based smoothing of Zhou & Shimada (thesis §4.6, ref. [135]: T. Zhou, K. Shimada, "An
// angle-based approach to two-dimensional mesh smoothing", IMR 2000) with a guard that never
// lowers the minimum angle and never inverts a cell.
//
// For an interior node i with edge-connected neighbours j = 1..n: at each neighbour j the
// segment (j -> i) splits the angle between the two cells A, B sharing edge (i, j) into
// alpha_A (corner angle of A at j) and alpha_B (corner angle of B at j). Zhou & Shimada rotate
// i about j so that the two become equal (triangles and quads alike) or, in a mixed mesh, reach
// the ideal ratio 60:90 of a triangle and a quad corner:
//     alpha_A' = (alpha_A + alpha_B) w_A / (w_A + w_B),  w = 60 deg (triangle) or 90 deg (quad),
//     P_j = x_j + R(s (alpha_A - alpha_A')) (x_i - x_j),   s = +1 if A lies counter-clockwise
//                                                            of (j -> i), else -1,
//     x_i_new = (1/n) sum_j P_j.
// (Only edge neighbours are used: for a quad, the diagonal node's angles are not 45:45 on an
// anisotropic rectangle, so including them would destroy aligned stretched quads; with edge
// neighbours a perfect grid of rectangles is a fixed point.)
//
// Guard (Gauss-Seidel, nodes in index order): a move is accepted only if every cell around i
// stays valid (all corner scaled Jacobians > 0), the minimum corner angle over those cells
// does not decrease, and their minimum corner sine (the scaled Jacobian, which also catches
// corners opening towards 180 degrees) does not decrease below min(its old value, min_sine);
// otherwise the displacement is halved (up to max_halvings times) and
// retried, else the node is left in place. Since a node only changes the angles of its own
// cells, the global minimum angle can never decrease and no cell can invert.
// Boundary nodes (on a free edge or a listed boundary edge) and hanging nodes are fixed.
//
// Metric space (optional NodeMetric T(x), e.g. the frame's M = V^-1 at x, det T > 0): node i's
// step is made with every angle measured between mapped edge vectors T_i (x_k - x_l), T_i =
// T(x_i) frozen for that node's step, the rotation done on T_i (x_i - x_j) and mapped back by
// T_i^-1; the guard measures the angles and sines in the same space. On a mesh that fits the
// frame the mapped cells are near-unit squares, so the smoothing straightens them without
// moving nodes by the physical-space angles of stretched cells (which, near a boundary layer,
// pull the first row of nodes away from the wall: docs/quadsmooth.md). The guarantees hold per
// node in its own T_i-space; validity (no inverted cell) holds in physical space as before.
#include <functional>

#include "mesh/mesh.hpp"

namespace quadapt {

struct SmoothOptions {
  int sweeps = 3;         ///< Gauss-Seidel passes over the interior nodes
  int max_halvings = 4;   ///< a rejected move is halved at most this many times
  double tolerance = 0;   ///< stop early when no node moves more than tolerance * local size
  double min_sine = 0.5;  ///< a move may lower the local minimum corner sine only while it stays above this
};

struct SmoothStats {
  int sweeps = 0;             ///< passes done
  bool converged = false;     ///< stopped on the tolerance (no node moved more than it), not on the sweeps cap
  int interior_nodes = 0;     ///< nodes allowed to move
  long moves_full = 0;        ///< accepted moves at the full step
  long moves_reduced = 0;     ///< accepted after halving
  long moves_rejected = 0;    ///< left in place
  int sliding_nodes = 0;      ///< shape fit: wall nodes that slide along a straight wall
  double min_angle_before = 0, min_angle_after = 0;  ///< degrees, whole mesh
  double max_displacement = 0;                       ///< largest accepted move (length units)
};

using Mat2 = Eigen::Matrix2d;
/// Linear map of the metric space at a point (the frame's M, det > 0); empty = physical space.
using NodeMetric = std::function<Mat2(const Vec2&)>;

/// Smooths m in place (conforming triangle, quad or mixed mesh, cells counter-clockwise), in
/// physical space or, with `metric`, in the metric space (see above).
SmoothStats angle_smooth(Mesh& m, const SmoothOptions& opt = {}, const NodeMetric& metric = {});

/// Corner-similarity smoothing in the metric (issue #14; the default of quadsmooth --frame).
///
/// The target of a quad is the unit square of the metric, of a triangle the equilateral one.
/// Every corner is fitted in the metric at its own node (cell_metric: at its cell's centroid): for a corner at x_j with next node x_n
/// and previous node x_p (counter-clockwise), T_j = metric(x_j) (evaluated once per sweep),
/// a0 = T_j (x_n - x_j), a1 = T_j (x_p - x_j), the best similarity z (a complex number:
/// rotation and scale) with z e0 ~ a0, z e1 ~ a1 (e0 = 1; e1 = i for a quad corner, e^{i pi/3}
/// for a triangle's) in the least-squares sense is
///     z = (a0 + conj(e1) a1) / 2,
/// its modulus clamped to [size_min, size_max] * target_edge. With every z fixed, node i moves
/// to the minimiser of the sum, over the corners it takes part in, of |a0 - z e0|^2 +
/// |a1 - z e1|^2 (quadratic in x_i: a 2x2 system; in a constant metric the mean of the
/// positions each corner asks for) — one Gauss-Seidel step of a local/global ("as rigid as
/// possible") fit of every corner to a square of the target size: it straightens corners AND
/// keeps edge lengths near the target, where angle_smooth only balances angles (and lets
/// lengths drift: on the constant 20:1 frames of docs/quad-quality.md, 10 angle sweeps lower
/// the edges in band from 95 % to 92 %). (Fitting every corner of node i's star in i's own
/// metric instead — an energy that changes with the node being moved — cost the S-shock loop
/// 1.6x in L2 error; with each corner in its own metric the loop's error falls, docs/quadsmooth.md.)
/// Guard (as angle_smooth's, without its minimum-angle rule): a move is accepted only if no cell
/// around the node that was valid inverts and the smallest corner sine of those cells does not
/// fall below min(its old value, min_sine) in node i's metric space, nor below min(its old
/// value, min_sine_physical) in physical space; otherwise it is halved, up to max_halvings
/// times, else skipped. (Without the physical rule the S-shock loop's graded frames got cells
/// of corner angle 0.0 degrees.) Nodes in index order (deterministic); hanging nodes fixed,
/// boundary nodes fixed except those that slide along a straight wall (slide_walls: the
/// minimiser of the same fit on the wall's line, docs/quadsmooth.md "Walls").
struct ShapeSmoothOptions {
  int sweeps = 30;            ///< Gauss-Seidel passes at most
  /// Over-relaxation (SOR) of an interior node's step: it moves by relaxation times the step to
  /// its fit's minimiser (then the guard below halves it if needed); 1 = plain Gauss-Seidel.
  /// Wall nodes sliding along a wall take the plain step. In (0, 2). The fit is stopped at the
  /// sweeps cap, not converged (the tolerance is rarely met), and 1.6 reaches in 25-30 sweeps
  /// the figures that 1 reaches in 60 (docs/quadsmooth.md, "Over-relaxation").
  double relaxation = 1.6;
  /// a node is visited again only while a node of its cells moved more than this times its mean
  /// edge length in the sweep before; stop when none did
  double tolerance = 1e-3;
  double target_edge = 1;     ///< ideal edge length in the metric space of `metric`
  double size_min = 0.85;     ///< the fitted scale is clamped to [size_min, size_max] * target_edge
  double size_max = 1.15;
  int max_halvings = 4;       ///< a rejected move is halved at most this many times
  double min_sine = 0.5;      ///< a move may lower the local minimum metric corner sine only while it stays above this
  double min_sine_physical = 0.05; ///< the same in physical space
  /// the metric of a corner: at its own node (false), or the cell's at its centroid (true; all
  /// corners of a cell in one metric, as meshquality --frame measures a cell). The guard above
  /// stays in the moving node's metric either way. Not the default: it raises the per-cell
  /// metric figures on rough frames but costs the adaptive loops accuracy (docs/quadsmooth.md).
  bool cell_metric = false;
  /// wall nodes slide along their wall where it is straight (wall_slides below): the node
  /// moves to the fit's minimiser on the line through its two wall neighbours, kept between them
  /// (at least 1/10 of the way from each), under the same guard. Off: every boundary node is fixed.
  bool slide_walls = true;
};

/// A boundary node that may slide: `node` lies on the straight segment between its two wall
/// neighbours `a` and `b` (within 1e-9 |b - a|, strictly between them).
struct WallSlide {
  int node = -1, a = -1, b = -1;
};

/// The boundary nodes of m that may slide along their wall: exactly two free edges (edges of one
/// cell), collinear (above); the boundary edges m lists at the node, if any, are those two and in
/// one group (so no corner and no end of a group moves); not a hanging node (its two free edges
/// are not halves of a cell edge a-b). In node order.
std::vector<WallSlide> wall_slides(const Mesh& m);

/// Smooths m in place (conforming quad, triangle or mixed mesh, cells counter-clockwise) by the
/// corner-similarity fit above, in the space mapped by `metric` (empty: physical space).
SmoothStats shape_smooth(Mesh& m, const ShapeSmoothOptions& opt = {}, const NodeMetric& metric = {});

/// T at a point, with a per-node hint for the lookup (in/out, -1 at first; e.g. the frame cell
/// the node was in at the last sweep). Must return what the lookup without the hint returns.
using HintedNodeMetric = std::function<Mat2(const Vec2&, int& hint)>;
/// shape_smooth with a hinted metric (quadsmooth: FrameSampler::at(x, hint), each node keeping
/// its frame cell between sweeps; the frame lookups were 11 % of the fit's instructions).
SmoothStats shape_smooth(Mesh& m, const ShapeSmoothOptions& opt, const HintedNodeMetric& metric);

}  // namespace quadapt
