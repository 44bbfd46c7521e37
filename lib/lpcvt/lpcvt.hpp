#pragma once
// The L_p-CVT mesh generator (thesis Algorithm 3): boundary equidistribution, interior seeding,
// cycles of { L-BFGS minimisation of the L_p-CVT energy (Algorithm 1); edge split/merge
// (Algorithm 2) } until fewer than `change_tol` of the edges change in two consecutive cycles
// (the tolerance ramps up to `change_tol_max` after `ramp_after` cycles when split/merge
// oscillates, §4.5), then the constrained Delaunay triangulation (§4.6).
//
// Multilevel start (option `multilevel`, lpcvt/multilevel.hpp): the cycles run first on the
// metric 2^-L M_eff with 4^-L of the points, then on every finer level from the children of the
// coarser sites, with the count set exactly at the start of each level (adjust_count).
//
// Point count. One point per unit metric area: the requested number of sites is
//   N_req = A_M + P_M / 2 + 1,  A_M = integral |det M_eff| (Background::metric_area),
//   P_M = metric length of the boundary,
// (a square lattice of spacing 1 on an a x a metric square has (a+1)^2 = A + P/2 + 1 sites),
// and about 2 A_M triangles.
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "lpcvt/background.hpp"
#include "lpcvt/boundary_points.hpp"
#include "lpcvt/metric_graph.hpp"
#include "lpcvt/optimize.hpp"
#include "lpcvt/seed.hpp"
#include "lpcvt/split_merge.hpp"
#include "mesh/mesh.hpp"

namespace quadapt {
class BoundaryGeometry;
}

namespace quadapt::lpcvt {

struct LpcvtOptions {
  double p = 6;                 ///< L_p exponent of the energy (eq. 4.1) and of eq. 4.12
  unsigned seed = 1;            ///< random seed of the interior points
  int initial_points = -1;      ///< interior points to start from; -1: the requested count
  SeedMode seed_mode = SeedMode::Density;
  int max_cycles = 30;          ///< split/merge cycles
  LbfgsOptions lbfgs;           ///< per-cycle minimisation
  SplitMergeOptions split;      ///< lmin, lmax (q is set to p)
  double change_tol = 0.02;     ///< fraction of edges split or merged counted as "no change"
  double change_tol_max = 0.05; ///< ramp limit
  int ramp_after = 5;           ///< cycles after which the tolerance ramps (+0.5% per cycle)
  double corner_angle = 30;     ///< degrees: boundary corners split curves
  int boundary_samples = 8;     ///< samples per background edge (analytic metrics)
  /// q of the boundary points' metric length |M_eff tau|_q (boundary_points.hpp): 2 = the thesis's
  /// eq. 4.2; 0 = the energy's exponent p (frames' default: one wall point per lattice row).
  double boundary_norm = 2;
  /// Whether q is a valid boundary_norm: 0 (the exponent p) or a norm's exponent in [1, 64].
  static bool valid_boundary_norm(double q) { return q == 0 || (q >= 1 && q <= 64); }
  bool polish = true;           ///< minimise once more after the last split/merge if it changed points
  bool multilevel = false;      ///< multilevel start (above); the coarsest level uses seed_mode
  int coarse_points = 250;      ///< multilevel: interior points of the coarsest level, at least
  double lattice_delta = 0.75;   ///< SeedMode::Lattice: rejection distance (metric units)
  /// SeedMode::Lattice: the lattice's translation (lattice units, each in [0, 1)) along the axes
  /// the walls do not register (lattice.hpp, lattice_points); lpcvt/phases.hpp tries several.
  Vec2 lattice_phase = Vec2::Zero();
  /// Return once the start (boundary points and seeds: LpcvtResult::initial_sites) is built, with
  /// no minimisation and no mesh (lpcvt/phases.hpp compares the phases' starts with it).
  bool start_only = false;
  /// SeedMode::Lattice: each interior start point moved by M_eff^-1 u, u uniform in the disk of
  /// this radius (metric units: target edges), drawn from `seed` in point order; a move that leaves
  /// the domain is not made. 0: the lattice as built (then `seed` changes nothing).
  double start_jitter = 0;
  /// The domain's true boundary (docs/curved.md): boundary points on its curves
  /// (geometry_boundary.hpp) instead of the background mesh's polygon, and its physical names as
  /// the output's boundary groups. Not owned; nullptr: the background's boundary.
  const BoundaryGeometry* geometry = nullptr;
  bool exact_count = true;      ///< set the point count to the requested one at the start of each
                                ///< level (multilevel) and before the polish, see adjust_count

  /// The lpcvt tool's defaults for frames: lattice start, relaxations until the points settle
  /// (RMS metric displacement at most 0.05 spacing over 10 iterations, or the energy falls by
  /// less than 1e-3 over 10; at most 300 iterations), energy weight |det M|^1 (docs/lpcvt.md,
  /// Convergence).
  static LpcvtOptions for_frame();
  /// The thesis's validation settings (§6.1): 20 uniform random start points, no exact count,
  /// lmin 0, lmax sqrt(2), the unweighted energy, L-BFGS to delta 1e-10.
  static LpcvtOptions for_analytic();
  /// Applies the tool's --init word (lattice, multilevel, density, uniform; empty = the
  /// default of the mode) to seed_mode, multilevel, initial_points and exact_count.
  void set_init(const std::string& init, bool analytic);
};

/// One level of the multilevel start (level 0 = the final metric).
struct LevelRecord {
  int level = 0;
  double scale = 1;             ///< metric factor 2^-level
  int points = 0, boundary_points = 0;
  int start_points = 0;         ///< sites at the start (children, before adjust_count)
  int cycles = 0, iterations = 0, evaluations = 0;
  double seconds = 0;
};

struct CycleRecord {
  int cycle = 0;
  int iterations = 0, evaluations = 0;
  double energy = 0, grad_norm = 0;
  bool converged = false;       ///< of the minimisation
  std::string stop;             ///< of the minimisation
  double window_move = -1;      ///< of the minimisation: the last RMS metric displacement over `past` iterations
  double window_edge_change = -1;  ///< ... and the last RMS metric change of the graph's edge vectors
  int points = 0;               ///< sites after the split/merge
  SplitMergeResult split;       ///< zero for the polish step
  double tolerance = 0;         ///< change tolerance used for this cycle
  bool polish = false;
  int level = 0;                ///< multilevel level (0 = final)
};

struct LpcvtResult {
  std::vector<Vec2> initial_sites;  ///< boundary sites then the seeds
  std::vector<Vec2> sites;          ///< final sites (boundary first)
  int nfixed = 0;                   ///< number of boundary sites
  BoundaryPoints boundary;
  long metric_flips = 0;            ///< metric cells: flips of the output triangulation (below)
  bool metric_flips_capped = false; ///< ... stopped at the cap: not the metric Delaunay triangulation
  std::vector<IterationRecord> history;
  std::vector<CycleRecord> cycles;
  std::vector<LevelRecord> levels;  ///< coarsest first; one entry without multilevel
  int iterations = 0, evaluations = 0;
  EnergyTimers energy_timers;      ///< summed over the minimisations (graph updates/rebuilds too)
  double energy = 0, grad_norm = 0;
  bool converged = false;          ///< outer loop converged and the last minimisation converged
  std::string stop;                ///< why it stopped, in words
  double requested_points = 0, metric_area = 0, boundary_metric_length = 0;
  double boundary_norm = 2;     ///< the q of the boundary's metric length actually used
  Mesh mesh;                       ///< the final triangulation
};

/// Runs Algorithm 3 on the background. `log` receives progress lines (may be empty).
LpcvtResult run_lpcvt(const Background& bg, const LpcvtOptions& opt,
                      const std::function<void(const std::string&)>& log = {});

/// Report figures: points, requested_points, triangles, iterations, evaluations, cycles,
/// energy, grad_norm, converged, stop, and the convergence history (per iteration and per cycle).
/// Point spacing in target cell edges is 1 / kSplit (recombine's split into four; run.hpp, Sizes).
constexpr double kSplit = 0.5;

/// The default M_eff / M of a quadapt-convention frame (frame/frame.hpp): kSplit * the cell-metric
/// factor = 1/4.
double frame_metric_scale();

/// Adds the cell field "Vinv" and its $FrameConvention tag to the triangles m (set_frame_field):
/// M_eff / frame_metric_scale() = 4 M_eff of the background cell at each centroid (the quadapt
/// convention, as --write-frame: the frame actually meshed, after
/// --complexity/--smooth/--gradation), so that recombine matches in the metric without --frame.
void attach_frame(Mesh& m, const Background& bg);

/// Makes the triangulation m Delaunay in bg's metric (metric_graph.hpp): Lawson flips with the
/// metric of the background cell at each flip quadrilateral's centroid; boundary edges are never flipped.
/// Returns the number of flips; *capped (when given): they stopped at the cap (kMaxFlipsPerSite),
/// so m is not Delaunay in the metric.
long metric_flip_triangles(Mesh& m, const Background& bg, bool* capped = nullptr);

nlohmann::json to_json(const LpcvtResult& r);

}  // namespace quadapt::lpcvt
