#pragma once
// Driver of FreeFEM's standalone BAMG, `ffbamg` (Debian package freefem++), for metric-driven
// anisotropic triangulation. Gmsh 4.8.4's own BAMG path corrupts rotated metrics (docs/design.md §1).
//
// Call: ffbamg -b BACKGROUND.mesh -M METRIC.mtr -o OUT.mesh -nbv N -v 0 [-splitpbedge]
//              [-ratio R] [-NbSmooth k]
// in a private temporary directory (removed afterwards). The background mesh's boundary edges
// (with their refs) define the geometry; the output's boundary edges carry the same refs. BAMG
// caps the metric so that one background edge is cut into at most 10 edges ("maxsubdiv"):
// the background must not be much coarser than 10x the finest requested edge.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "bamg/inria_mesh.hpp"
#include "core/error.hpp"

namespace quadapt {

struct FfbamgOptions {
  std::string executable;       ///< default: $QUADAPT_FFBAMG, else "ffbamg" on PATH
  int max_vertices = 2000000;   ///< -nbv
  double gradation = 0;         ///< -ratio: metric smoothing bounding the size growth (0 = none)
  bool split_boundary_edges = true;  ///< -splitpbedge: split interior edges joining two boundary vertices
  int smoothing_iterations = 3;      ///< -NbSmooth (BAMG's node smoothing; its default is 3)
};

/// ffbamg could not be started (not installed, not executable): the machine's problem, not the
/// input's, so callers that name their input in ffbamg's failures leave this one as it is.
struct FfbamgNotRunnable : ExternalError {
  using ExternalError::ExternalError;
};

struct FfbamgResult {
  InriaMesh mesh;
  double seconds = 0;
  std::string command;  ///< the command line that was run (for reports)
};

/// Runs ffbamg on `background` (triangles; boundary edges with refs) with the per-vertex metric
/// `metric` (#background vertices SPD tensors). Throws FfbamgNotRunnable when ffbamg cannot be
/// started, ExternalError when it fails, or writes no mesh (the message includes the tail of its output).
FfbamgResult run_ffbamg(const InriaMesh& background, const std::vector<Eigen::Matrix2d>& metric,
                        const FfbamgOptions& opt = {});

}  // namespace quadapt
