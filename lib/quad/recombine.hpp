#pragma once
// Triangles -> all-quad mesh (thesis §4.6): parity fix, Blossom-Quad (Gmsh), split to all-quad.
//
//  1. check_triangulation (counter-clockwise triangles, boundary edges are free edges);
//  2. if the triangle count is odd, split the boundary triangle with the longest boundary edge
//     at that edge's midpoint (so that Blossom finds a perfect matching instead of falling back
//     to greedy matching);
//  3. blossom_recombine (quad-dominant mesh, orientation/area/boundary checked);
//  4. split_to_all_quads (each quad -> 4, each remaining triangle -> 3, exact midpoints).
// The boundary groups (names and tags) are carried through every step.
#include "mesh/mesh.hpp"
#include "quad/blossom.hpp"
#include "quad/boundary_corners.hpp"
#include "quad/metric_matching.hpp"
#include "quad/quality_summary.hpp"

namespace quadapt {

struct RecombineOptions {
  /// The matching: metric (quad/metric_matching.hpp; needs `frame`) or Gmsh's Blossom.
  enum class Matching { Metric, Blossom } matching = Matching::Blossom;
  std::vector<Eigen::Matrix2d> frame;  ///< Metric: one frame matrix M per input triangle
  MetricMatchingOptions metric;
  BlossomOptions blossom;
  bool split = true;  ///< false: stop at the quad-dominant mesh (for inspection)

  /// The recombine tool's choice when a frame is known (TRI's cell field Vinv or --frame): the
  /// metric matching on M, one oriented frame matrix per input triangle — Frame::at_cells(tri)
  /// for a frame of its own background, frame_from_mesh(tri, path).oriented() for TRI's Vinv.
  /// Keeps the other options. The default-built options use Blossom (no frame needed).
  RecombineOptions& with_frame(std::vector<Eigen::Matrix2d> M) {
    frame = std::move(M);
    matching = Matching::Metric;
    return *this;
  }
};

struct RecombineStats {
  int triangles_in = 0;              ///< triangles of the input
  bool parity_split = false;         ///< one boundary triangle was split to make the count even
  BlossomStats blossom;              ///< quads / triangles after Blossom
  MetricMatchingStats metric;        ///< quads / triangles after the metric matching
  BoundaryCornerStats corners;       ///< flat boundary corners found / split away (boundary_corners.hpp)
  int cells_out = 0;                 ///< cells of the result (all quads when split)
  QualitySummary quality;            ///< of the result
};

/// Runs steps 1-4 (with the metric matching: 1, 3 = metric_pairing, 4; no parity split: the
/// matching need not be perfect) on `tri` (path is only used in error messages).
Mesh recombine_to_all_quads(const Mesh& tri, const RecombineOptions& opt = {}, RecombineStats* stats = nullptr,
                            const std::string& path = "mesh");

}  // namespace quadapt
