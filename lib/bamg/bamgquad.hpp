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
  bool log_euclidean = true;   ///< vertex metric: log-Euclidean (else arithmetic) mean of the cells'
  FfbamgOptions ffbamg;
  RecombineOptions recombine;
};

struct BamgQuadStats {
  int frame_cells = 0;
  double target_complexity = 0;  ///< int |det M| / 4 dA: the frame's continuous cell count
  double edge_factor = 0;
  int bamg_vertices = 0, bamg_triangles = 0;
  double bamg_seconds = 0;
  std::string bamg_command;
  RecombineStats recombine;      ///< Blossom and split figures, quality of the result
  int cells = 0;                 ///< cells of the all-quad result
  double complexity_ratio = 0;   ///< cells / target_complexity
};

/// Runs the whole path on a frame mesh (cells with the 9-component 'Vinv' field, boundary
/// groups). `path` names the frame in error messages. Throws InputError for a bad frame
/// (missing/singular/non-finite Vinv, unsupported boundary), ExternalError when ffbamg or Gmsh
/// fail, NumericalError when the result has inverted cells.
Mesh bamg_quad(const Mesh& frame, const BamgQuadOptions& opt = {}, BamgQuadStats* stats = nullptr,
               const std::string& path = "frame");

}  // namespace quadapt
