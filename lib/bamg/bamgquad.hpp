#pragma once
// The thesis's BAMG benchmark path (ch. 6, §3.4): frame -> Riemannian metric 𝓜 = M^T M ->
// anisotropic triangles by FreeFEM's BAMG (ffbamg) -> Blossom-Quad (Gmsh) -> all-quad split.
// Sizes are doubled for the split (frame_metric.hpp; docs/bamgquad.md).
#include <string>

#include "bamg/ffbamg.hpp"
#include "frame/frame.hpp"
#include "mesh/mesh.hpp"
#include "quad/recombine.hpp"

namespace quadapt {

struct BamgQuadOptions {
  double edge_factor = 0;      ///< BAMG unit edge in frame half-axes; 0 = default_bamg_edge_factor()
  bool log_euclidean = true;   ///< vertex metric: log-Euclidean (else arithmetic) mean of the cells'
  /// Complexity calibration on BAMG's count: when the predicted cell count 2 T (T = BAMG's
  /// triangles; kCellsPerBamgTriangle) misses the frame's target by more than
  /// calibration_tolerance (relative), the whole metric is multiplied by target / (2 T) (the
  /// density scales like sqrt(det 𝓜)) and BAMG is run again, at most max_runs times in all; the
  /// run closest to the target goes through Blossom-Quad and the split, once — again (with the
  /// measured cells per triangle) only when that count still misses and BAMG runs remain; the
  /// all-quad mesh closest to the target is kept. max_runs = 1: off.
  int max_runs = 3;
  double calibration_tolerance = 0.03;
  FfbamgOptions ffbamg;
  RecombineOptions recombine;
};

/// All-quad cells per BAMG triangle predicted by the calibration: the split makes 4 cells of a
/// quad and 3 of a triangle, so T triangles paired into q quads leaving t give 4q + 3t = 2T + t.
constexpr double kCellsPerBamgTriangle = 2.0;

struct BamgQuadStats {
  int frame_cells = 0;
  double target_complexity = 0;  ///< Frame::target_cells(): the frame's continuous cell count
  double edge_factor = 0;
  int bamg_vertices = 0, bamg_triangles = 0;
  double bamg_seconds = 0;       ///< ffbamg wall time, all runs
  std::string bamg_command;
  RecombineStats recombine;      ///< Blossom and split figures, quality of the result
  int cells = 0;                 ///< cells of the all-quad result
  double complexity_ratio = 0;   ///< cells / target_complexity
  int runs = 0;                  ///< BAMG runs made (calibration)
  int blossom_runs = 0;          ///< Blossom-Quad runs (1 unless its count missed, above)
  double metric_factor = 1;      ///< calibration factor applied to 𝓜 in the kept run
  double first_ratio = 0;        ///< predicted cells (2 T) / target of the first, uncalibrated run
  double predicted_ratio = 0;    ///< predicted cells (2 T) / target of the kept run
};

/// Runs the whole path on a frame (frame/frame.hpp: its background's boundary groups are kept).
/// `path` names the frame in error messages. Throws InputError for an unsupported boundary,
/// ExternalError when ffbamg or Gmsh fail, NumericalError when the result has inverted cells.
Mesh bamg_quad(const Frame& frame, const BamgQuadOptions& opt = {}, BamgQuadStats* stats = nullptr,
               const std::string& path = "frame");

}  // namespace quadapt
