#pragma once
// The bending number of a frame: how fast its long axis turns along itself, against its stretch.
//
// Per background cell with half-axes h1 >= h2 (quadapt convention) and long axis v:
//     B = κ h1^2 / h2,   κ = |∇θ · v|  (1/length: the curvature of the rows of target cells),
// θ the long axis's angle, its gradient fitted by least squares to the face neighbours'
// differences of θ (mod π; neighbours of stretch < kMinBendingStretch left out). A row of target
// cells along v leaves its tangent by κ h1^2 / 2 = (B/2) h2 over a distance h1: for B of order 1
// and more a straight-edged row bends by a short edge within a few long ones.
//
// Why it matters (docs/quad-quality.md, "Curved anisotropy"): lpcvt's Voronoi cells take the
// metric as constant over each background cell, so a site's cell reaches about 2 h1 along the
// straight tangent, which a curved row leaves after B h2 ... lpcvt's points are two target cells
// apart. Measured on a quarter-circle boundary layer (radius 0.6, h1 = 0.05 along it, 48 x 48
// background): B up to 0.8 / 1.6 / 3.8 / 7.6 at stretch 10 / 20 / 50 / 100 gave 93 / 84 / 74 / 39 %
// of the edges in the metric's band; on 192 x 192, at stretch 100, trapezoids following the circles
// have 100 %.
#include <vector>

#include "frame/frame.hpp"
#include "mesh/mesh.hpp"

namespace quadapt {

/// Cells whose stretch h1/h2 is below this have no long axis to speak of: B = 0 there, and they
/// take no part in their neighbours' fits.
constexpr double kMinBendingStretch = 1.5;

/// B per cell of `background` (#cells) for the frame M (#cells, quadapt convention, reflections
/// allowed: only M^T M is used). 0 where the stretch is below kMinBendingStretch or fewer than two
/// neighbours (spanning the plane) have a long axis.
std::vector<double> frame_bending(const Mesh& background, const std::vector<Mat2>& M);

struct BendingSummary {
  double share_over_1 = 0;  ///< share of the target cells (area |det M| / 4) where B > 1
  double share_over_2 = 0;  ///< ... where B > 2
  double max = 0;           ///< largest B
};

/// The summary of frame_bending(background, M), weighted by target cells.
BendingSummary summarize_bending(const Mesh& background, const std::vector<Mat2>& M, const std::vector<double>& B);

}  // namespace quadapt
