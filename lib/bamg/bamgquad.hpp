#pragma once
// The thesis's BAMG benchmark path (ch. 6, §3.4): frame -> Riemannian metric 𝓜 = M^T M ->
// anisotropic triangles by FreeFEM's BAMG (ffbamg) -> Blossom-Quad (Gmsh) -> all-quad split.
// Sizes are doubled for the split (frame_metric.hpp; docs/bamgquad.md).
#include <string>

#include "bamg/ffbamg.hpp"
#include "mesh/mesh.hpp"
#include "quad/recombine.hpp"

namespace quadapt {

struct BamgQuadOptions {
  double edge_factor = 0;      ///< BAMG unit edge in frame half-axes; 0 = default_bamg_edge_factor()
  /// M is multiplied by this first: 1 for quadapt frames (d = |det M|/4, docs/design.md §4), 2 for
  /// PHiLiP's files, whose sizes are full edges (d = |det M|; the same as lpcvt --convention philip).
  double frame_scale = 1;
  bool log_euclidean = true;   ///< vertex metric: log-Euclidean (else arithmetic) mean of the cells'
  /// Complexity calibration: when the all-quad mesh's cell count misses the frame's target by
  /// more than calibration_tolerance (relative), the whole metric is multiplied by
  /// target / cells (the cell density scales like sqrt(det 𝓜)) and the path is run again, at
  /// most max_runs times in all; the run closest to the target is kept. max_runs = 1: off.
  int max_runs = 3;
  double calibration_tolerance = 0.03;
  FfbamgOptions ffbamg;
  RecombineOptions recombine;
};

struct BamgQuadStats {
  int frame_cells = 0;
  double target_complexity = 0;  ///< int |det M| / 4 dA: the frame's continuous cell count
  double edge_factor = 0;
  int bamg_vertices = 0, bamg_triangles = 0;
  double bamg_seconds = 0;       ///< ffbamg wall time, all runs
  std::string bamg_command;
  RecombineStats recombine;      ///< Blossom and split figures, quality of the result
  int cells = 0;                 ///< cells of the all-quad result
  double complexity_ratio = 0;   ///< cells / target_complexity
  int runs = 0;                  ///< BAMG + Blossom runs made (calibration)
  double metric_factor = 1;      ///< calibration factor applied to 𝓜 in the kept run
  double first_ratio = 0;        ///< cells / target of the first, uncalibrated run
};

/// Runs the whole path on a frame mesh (cells with the 9-component 'Vinv' field, boundary
/// groups). `path` names the frame in error messages. Throws InputError for a bad frame
/// (missing/singular/non-finite Vinv, unsupported boundary), ExternalError when ffbamg or Gmsh
/// fail, NumericalError when the result has inverted cells.
Mesh bamg_quad(const Mesh& frame, const BamgQuadOptions& opt = {}, BamgQuadStats* stats = nullptr,
               const std::string& path = "frame");

}  // namespace quadapt
