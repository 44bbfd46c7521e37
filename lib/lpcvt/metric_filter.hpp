#pragma once
// Optional filters of the piecewise-constant frame before meshing (beyond the thesis, whose
// generator used the raw per-cell frame and stalled at sharp size changes, §6.2-6.5, §7.1.1).
// Both work on the effective metric M_eff per background cell and keep the point count: the
// result is rescaled uniformly to the metric area it had before (lpcvt.hpp: one point per
// unit metric area), so they redistribute points and never change the complexity.
//
// Smoothing (log-Euclidean). The Riemannian metric 𝓜 = M^T M of each cell is replaced,
// `passes` times, by the mean of log 𝓜 over the cell and its face neighbours,
//     log 𝓜_c <- (log 𝓜_c + sum_n log 𝓜_n) / (1 + #n),      𝓜 = exp(log 𝓜)
// (Arsigny et al.'s log-Euclidean mean: symmetric positive definite by construction, no angle
// wrap-around as when averaging theta, no swelling of the determinant as the arithmetic mean).
// The frame is rebuilt as M = diag(sqrt(mu_1), sqrt(mu_2)) [e_1 e_2]^T from the eigenpairs of
// 𝓜; where the smoothed metric is nearly isotropic (mu_max / mu_min < 1.1^2) the eigenvectors
// mean nothing and the cell gets the isotropic frame of that size turned like its own frame
// (the rotation nearest to M; the L_p energy, unlike 𝓜, sees the frame's orientation even when
// h1 = h2). A cell whose smoothed log 𝓜 equals its own (a constant frame) keeps M bit for bit.
//
// Gradation (Alauzet's anisotropic size gradation, "Size gradation control of anisotropic
// meshes", 2010). Between face-neighbouring cells c, n with centroids g_c, g_n,
//     𝓜_n <- 𝓜_n ∩ eta(l) 𝓜_c,   l = |M_c (g_n - g_c)| (metric length in c's metric),
//     eta(l) = (1 + l ln beta)^-2,
// i.e. along every direction the size at n may exceed the size at c by at most the factor
// (1 + l ln beta): sizes grow by about beta per unit metric length (per element). ∩ is the
// metric intersection (largest ellipse inside both, by simultaneous reduction). A worklist
// re-imposes the bounds of every cell that changed on its neighbours until nothing changes by
// more than 1e-9 (relative; at most 200 updates per cell), taking the finest cell first (largest
// det 𝓜; cells of equal det and equal metric one by one, lower index first; different metrics of
// equal det, as diag(a, b) beside diag(b, a), as one group from a snapshot, each neighbour taking
// their bounds sorted by the generalized eigenvalues), so the result depends on the metrics, not
// on the numbering: a turned or mirrored frame grades to the turned or mirrored metrics (to
// rounding). Intersection only
// refines; the uniform rescale afterwards restores the point count. The frame is rebuilt from
// 𝓜 as for the smoothing.
#include <optional>

#include "lpcvt/background.hpp"

namespace quadapt::lpcvt {

struct FilterReport {
  int cells_changed = 0;      ///< cells whose metric moved by more than 1e-12 (relative)
  int passes = 0;             ///< gradation: metric updates made
  double rescale = 1;         ///< the uniform factor that restored the metric area
  double max_ratio_before = 0, max_ratio_after = 0;  ///< largest neighbour size ratio
};

/// How far the metric is from constant: max over the integration cells c of
/// || log 𝓜_c − L̄ ||_F, 𝓜_c = M_cᵀ M_c (so reflections and the frame's turn inside an isotropic
/// 𝓜 do not count), L̄ the area-weighted mean of log 𝓜 (Arsigny's log-Euclidean mean). Natural
/// log units: 0 for a constant frame (to rounding); a size ratio s between two cells counts
/// 2 ln s between them, a 10:1 frame turned by θ about 2 ln(10) sin θ. Analytic backgrounds: at
/// the cells' centroids.
double metric_spread(const Background& bg);

/// Log-Euclidean smoothing, `passes` Jacobi passes (above).
FilterReport smooth_metric(Background& bg, int passes);

/// Anisotropic gradation (above); growth beta > 1 per unit metric length.
FilterReport grade_metric(Background& bg, double beta);

/// lpcvt's frame filters in their order (run.cpp; fit_frame.hpp repeats them for quadsmooth):
/// smooth_metric when passes > 0, then grade_metric when beta > 0 (the caller checks beta > 1).
struct FilterReports {
  std::optional<FilterReport> smoothing, gradation;  ///< each when it ran
};
FilterReports filter_metric(Background& bg, int passes, double beta);

/// The floor (fit_frame.hpp, "capped"): per background cell the metric intersection
/// 𝓜_c ∩ 𝓕_c with 𝓕_c = F_cᵀ F_c (`floor`: one M per mesh cell, in the background's units), i.e.
/// never coarser than F_c along any direction, then the uniform rescale to the metric area before.
/// A cell whose metric already contains its floor keeps its frame bit for bit (before the rescale).
/// Throws NumericalError when `floor` is not one matrix per mesh cell.
FilterReport cap_metric(Background& bg, const std::vector<Mat2>& floor);

/// Largest mean-size ratio between face-neighbouring background cells.
double max_neighbour_size_ratio(const Background& bg);

}  // namespace quadapt::lpcvt
