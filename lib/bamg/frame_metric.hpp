#pragma once
// From a frame field (per-cell M = V^-1, docs/design.md §3-4) to BAMG's input: the background
// triangulation and a per-vertex Riemannian metric.
//
// Sizes (docs/bamgquad.md). The frame's target element is the parallelogram with edges 2 h1,
// 2 h2 (area 4 h1 h2). bamgquad splits every quad of Blossom's output into 4, so the triangles
// must be twice as long: pre-split quads of 4 h1 x 4 h2 (area 16 h1 h2), i.e. triangles of area
// 8 h1 h2. BAMG makes triangles that are equilateral with unit edges in its metric 𝓜_b (metric
// area sqrt(3)/4). With 𝓜_b = s M^T M (det M = 1/(h1 h2)) a triangle's physical area is
// (sqrt(3)/4) h1 h2 / s, so s = sqrt(3)/32: BAMG's unit edge is edge_factor = sqrt(32/sqrt(3))
// = 4.2985 frame half-axes along each axis (the naive "unit length at 4 h", s = 1/16, makes
// triangles 13% smaller and overshoots the cell count by 15%).
//   𝓜_b = M^T M / edge_factor^2.
// Vertex metric: the area-weighted log-Euclidean mean of the adjacent cells' metrics,
//   𝓜_v = exp( sum_c a_c log 𝓜_c / sum_c a_c ),
// i.e. sizes averaged geometrically (log h) and directions blended through the matrix log; it
// keeps det (hence the element density sqrt(det 𝓜)) at the geometric mean, whereas the
// arithmetic mean of the tensors is dominated by the smallest size across a jump and inflates
// the cell count (option: arithmetic, for comparison).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "bamg/inria_mesh.hpp"
#include "mesh/mesh.hpp"

namespace quadapt {

/// sqrt(32 / sqrt(3)): BAMG unit edge in frame half-axes for the all-quad split (see above).
double default_bamg_edge_factor();

/// Riemannian metric 𝓜 = M^T M / edge_factor^2 of each frame matrix.
std::vector<Eigen::Matrix2d> bamg_cell_metrics(const std::vector<Eigen::Matrix2d>& M, double edge_factor);

/// Per-node metrics of `frame` from per-cell metrics: area-weighted log-Euclidean mean (or
/// arithmetic mean when log_euclidean = false) over the cells containing the node.
std::vector<Eigen::Matrix2d> vertex_metrics(const Mesh& frame, const std::vector<Eigen::Matrix2d>& cell_metric,
                                            bool log_euclidean = true);

/// BAMG background: the frame's nodes; quads split along their shorter diagonal; boundary edges
/// with ref = group index + 1; corners = nodes where the boundary changes group or turns by
/// more than 30 degrees. Requires every free edge of the frame to be a boundary edge.
InriaMesh bamg_background(const Mesh& frame);

/// Converts BAMG's output into a Mesh: triangles made counter-clockwise; boundary = the free
/// edges, each assigned to the group of the nearest boundary edge of `reference` (geometric
/// matching: the midpoint's distance to the reference's boundary segments), groups copied.
Mesh mesh_from_bamg(const InriaMesh& bm, const Mesh& reference);

}  // namespace quadapt
