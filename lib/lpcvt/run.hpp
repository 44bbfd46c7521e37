#pragma once
// The lpcvt tool as library calls, with the tool's defaults (docs/lpcvt.md): the background a
// frame (or the thesis's saddle metric) gives after the optional filters and rescales, then
// run_lpcvt with the output checks and the report figures.
//
// Sizes: lpcvt's points are two target cell edges apart, since recombine pairs the triangles
// into quads and splits every quad into four (halving the edges): M_eff = kSplit * the frame's
// cell metric (frame/frame.hpp), i.e. points 4 h1 x 4 h2 apart in the quadapt convention. The
// final all-quad cells the background asks for are metric_area / kSplit^2 (= 2 per triangle).
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "frame/frame.hpp"
#include "lpcvt/background.hpp"
#include "lpcvt/lpcvt.hpp"

namespace quadapt::lpcvt {

/// Everything the lpcvt tool sets besides LpcvtOptions.
struct LpcvtJob {
  LpcvtOptions lpcvt = LpcvtOptions::for_frame();
  double scale = 0;               ///< M_eff = scale * M (quadapt M); 0: frame_metric_scale() (frames), 1 (analytic)
  int smooth = 0;                 ///< log-Euclidean smoothing passes of the metric (metric_filter.hpp)
  double gradation = 0;           ///< size gradation (> 1), 0 = none
  bool free_orientation = false;  ///< turn the nearly isotropic cells to the boundary-aligned cross field (cross_field.hpp)
  double complexity = 0;          ///< target DOFs (with degree): cells = complexity / (degree+1)^2; 0 = the frame's
  int degree = -1;
  double cells_per_triangle = 2;  ///< final cells per triangle recombine gives: the point count is sized by 2/R
  bool metric_cells = true;       ///< Voronoi cells in the metric (Background::set_metric_cells); false: the thesis's
  double cell_anisotropy = 0.9;   ///< with metric_cells: the cells' anisotropy is the metric's to this power (0..1)
  /// Lattice start: run from this many lattice phases and keep the best recombined one
  /// (lpcvt/phases.hpp); 1 = phase 0 only; 0 = auto_phases(). Ignored for the other starts.
  int phases = 0;
  /// The most points a run may be asked for (metric area; 0 = no limit): about 1.4 kB of memory
  /// each (1.55 GB at 1.1e6 points, docs/bench-lpcvt.md), so 1e7 is ~14 GB. A frame far beyond
  /// it is nearly always a unit or convention mistake; check_point_budget refuses it up front.
  double max_points = 1e7;

  /// The lpcvt tool's defaults for a frame (docs/lpcvt.md): LpcvtOptions::for_frame(), metric
  /// cells, --smooth 4, --gradation 2, --orientation boundary.
  static LpcvtJob for_frame();
  /// The defaults of --analytic (the thesis's validation): LpcvtOptions::for_analytic(),
  /// Euclidean cells, no filters, the frame's own orientation.
  static LpcvtJob for_analytic();
};

/// Throws InputError naming the field ("LpcvtOptions::p = 0: the L_p exponent must be in [2, 32]
/// (lpcvt --lp-exponent)") when an option of `job` is outside the range the lpcvt tool accepts for
/// it; frame_background, saddle_background and mesh_background call it first (they ran with p = 0
/// or a negative scale and returned a poor mesh: a library user's review, session 38).
void check_job(const LpcvtJob& job);

/// Throws InputError(path, ...) when `bg` asks for more than job.max_points points (its metric
/// area), before any point is made.
void check_point_budget(const Background& bg, const LpcvtJob& job, const std::string& path);

/// How far a frame's cells reach across its domain (docs/lpcvt.md, "A frame that spans the
/// domain"): per background cell, the domain's extent along the cell's long axis v (the largest
/// minus the smallest v . x over its nodes) over the target cell's length 2 h1 — the number of
/// such cells across the domain along that axis — and the cell's stretch h1 / h2; each is the
/// median over the cells weighted by the points they ask for (metric area), so a few coarse cells
/// of a graded frame do not count.
struct FrameSpan {
  double cells_across = 0;  ///< target cells across the domain along the long axis (weighted median)
  double stretch = 1;       ///< h1 / h2 (weighted median)
  /// target cells along the long axis on the chord through the cell's centroid (the line along v
  /// clipped by the domain's convex hull; weighted median): a row's length, which cells_across
  /// (the extent) overstates on a turned domain (a square at 30 degrees: chord 1.155, extent 1.366)
  double cells_along_chord = 0;
};
/// The span of the frame the background meshes (M = M_eff / frame_metric_scale()).
FrameSpan frame_span(const Background& bg);
/// Below this many cells across, fewer than two of lpcvt's points (two cells apart) fit across the
/// domain's extent: measured on constant frames, every point then lies on the boundary at 30 and
/// 45 degrees (up to 3.6 and 3.5 cells) and every cell reaches from wall to wall; the frames of
/// the tests, PHiLiP's and the constant frames of stretch 1-20 ask for 7 or more.
constexpr double kMinCellsAcross = 4;
/// Below this many cells along a chord, rows are too short to keep the frame's lengths: lpcvt's
/// points are two target cells apart, so a row holds an even number of cells, and a row of 3.2
/// cells gets 2 or 4 (a review, session 35, constant frames of stretch 50-300 at 0-75 degrees:
/// 3.2-5.5 cells along the chord gave 70-94 % of the edges in band and up to 13 % irregular
/// vertices, 6.3 or more met issue #14's item 1 but for one row at 94.2 %).
constexpr double kMinCellsAlongChord = 6;
/// ... at a median stretch of at least this: nearly isotropic frames keep their quality at 5 cells
/// along a chord (a review: stretch 1 and 2, 93.5 and 97.5 % of the edges in band, 0-2 irregular
/// vertices), stretch 5, 10, 20 do not (93.0, 92.9, 95.0 %; 4.2-8.5 % irregular at 5.2 cells).
constexpr double kMinRowStretch = 3;
/// The warning for a span below kMinCellsAcross (what the frame asks, what comes out, what to
/// change), else for one below kMinCellsAlongChord, or "" for none.
std::string frame_span_warning(const FrameSpan& s);

/// Above this share of the target cells with a bending number over 2 (frame/bending.hpp, on the
/// frame lpcvt meshes, after its smoothing), the frame's rows bend faster than lpcvt's cells can
/// follow: on a quarter-circle layer (radius 0.6, h1 = 0.05, 48 x 48 background) shares of 0 / 0 /
/// 0.28 / 0.43 at stretch 10 / 20 / 50 / 100 gave 93 / 84 / 74 / 39 % of the edges in band (h1 = 0.02,
/// stretch 100: 0.34, 69 %); PHiLiP's step-3 frames and the studies' loop frames have at most 0.003.
constexpr double kBendingWarningShare = 0.1;
/// The warning for a frame's bending summary, or "" for none.
std::string frame_bending_warning(double share_over_2, double max);

/// The background of a frame: M_eff = scale * M, then --smooth/--gradation/--orientation, the complexity
/// rescale and the cells-per-triangle factor. Writes report keys smoothing, gradation,
/// orientation, frame_cells, complexity, degree, metric_rescale, target_cells, cells_per_triangle,
/// frame_span (cells_across_long_axis, cells_along_chord, stretch, warning: frame_span_warning or
/// null), frame_bending (share_over_1, share_over_2, max, warning or null) and
/// options.metric_scale, options.cells. The saddle background's default is Euclidean cells
/// (set job.metric_cells = false for the thesis's validation, as the tool does). Throws InputError for inconsistent options.
Background frame_background(const Frame& f, const LpcvtJob& job, nlohmann::json& report,
                            const std::function<void(const std::string&)>& log = {});
/// The thesis's validation background: the saddle metric (eq. 6.1) on [-1.3,1.3]^2 over a
/// grid x grid background, analytic or sampled at the cell centres; same filters and keys.
Background saddle_background(int grid, bool sampled, const LpcvtJob& job, nlohmann::json& report,
                             const std::function<void(const std::string&)>& log = {});

/// The default number of lattice phases: kAutoPhases where the frame is constant — its
/// metric_spread (metric_filter.hpp) at most kAutoPhaseSpread — and asks for at most
/// kAutoPhasePoints points (metric area); 1 otherwise. On a constant frame the lattice start
/// survives the minimisation and its translation decides where the rows end on oblique walls
/// (docs/lpcvt.md, Method 11); above 4000 points the walls' rows are a small share of the points
/// and the phase changes the irregular vertices by < 1 %. On a graded frame the rows bend and the
/// phases are four draws of the same lottery: on the study loops' 300 frames the best of four
/// had 0.0687 of the interior vertices irregular against 0.0754 for one phase (0.0755 for the
/// phase chosen after 20 iterations: the outcome is decided late), at 3.6x lpcvt's time, and no
/// loop error we can tell apart (docs/studies.md). Six phases, not four, since the loops stopped
/// paying for them: on the 432 constant-frame chains of docs/quad-quality.md six miss none of
/// issue #14's item 1 targets, four miss two (irregular 3.07 %, 3.09 %).
constexpr int kAutoPhases = 6;
constexpr double kAutoPhasePoints = 4000;
constexpr double kAutoPhaseSpread = 0.1;
int auto_phases(const Background& bg);
/// The same rule from the background's metric area and metric_spread, when the caller has them.
int auto_phases(double metric_area, double spread);

/// run_lpcvt (from job.phases lattice phases, keeping the best: lpcvt/phases.hpp), the check of
/// the output triangulation (NumericalError when invalid), and the report figures (to_json,
/// areas, angles, Voronoi alignment, expected_cells; with phases > 1 "phases": one entry per
/// phase run, and "phase": the index kept).
LpcvtResult mesh_background(const Background& bg, const LpcvtJob& job, nlohmann::json& report,
                            const std::function<void(const std::string&)>& log = {});

/// The frame actually meshed (after filters and rescales), quadapt convention: M = M_eff / frame_metric_scale().
Frame meshed_frame(const Background& bg);

/// The initial and final clipped Voronoi diagrams with the convergence history (JSON).
nlohmann::json voronoi_report(const Background& bg, const LpcvtResult& r, const nlohmann::json& report);

}  // namespace quadapt::lpcvt
