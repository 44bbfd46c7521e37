#pragma once
// Mesh quality figures reported by the meshquality tool (docs/meshquality.md), in physical
// space and, given a frame (frame/frame.hpp, in the quadapt convention), in its metric space.
//
// Metric space: each cell's vertices are mapped by the M (reflection removed) of the background
// cell that contains the cell's centroid (FrameSampler; a centroid outside the background takes
// the nearest background cell and is counted in frame.cells_outside).
// Metric edge length of an edge e of a cell: |N e| with N = Frame::cell_metric, in which a
// target cell's edge has length exactly 1; edges count per cell (an edge shared by two cells is
// measured twice, once with each cell's M).
// Continuous element count of the frame: Frame::target_cells() (thesis eq. 5.1).
// Curved cells (geometric order q >= 2) are measured on their map (quality/measures.hpp,
// curved_cell_shape): angles between the curved edges' tangents, the scaled Jacobian sampled on
// the map, arc lengths; in metric space the control points are mapped by M (the metric-space
// cell of a linear M is the mapped map). The area is the integral of det J (mesh.hpp).
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "frame/frame.hpp"
#include "mesh/mesh.hpp"

namespace quadapt {

/// Angle and Jacobian figures over a set of cells (in one space).
struct ShapeStats {
  double angle_min_deg = 0, angle_max_deg = 0, angle_mean_deg = 0;  ///< over all corners
  double quad_angle_share_80_100 = 0;  ///< share of quad corners with angle in [80, 100] degrees
  double quad_angle_deviation_mean_deg = 0;  ///< mean over quad corners of |angle - 90|
  double scaled_jacobian_min = 0, scaled_jacobian_mean = 0;           ///< over cells (cell minimum)
  double edge_ratio_median = 0;       ///< median over quads of longest / shortest edge
  double orientation_median_deg = 0;  ///< axial median over quads of the longest edge's direction
};

struct EdgeLengthStats {
  int edges = 0;  ///< cell edges measured (shared edges twice)
  double min = 0, max = 0, mean = 0, median = 0;
  double share_in_range = 0;  ///< share with 1/sqrt(2) <= length <= sqrt(2)
};

struct FrameStats {
  std::string file;
  int cells = 0;                      ///< background cells
  double continuous_complexity = 0;   ///< Frame::target_cells()
  double stretch_median = 0;          ///< median of sigma_max / sigma_min of M (= h_long / h_short)
  double orientation_median_deg = 0;  ///< axial median of the long axis (the h_long direction)
  int cells_outside = 0;              ///< mesh cells whose centroid lies outside the background
};

struct QualityReport {
  int nodes = 0, cells = 0, quads = 0, triangles = 0;
  int geometric_order = 1;            ///< of the cells (mesh/curved.hpp); > 1: measured on the curved map
  double area = 0;
  std::vector<BoundaryGroup> groups;
  std::vector<int> group_edges;
  int interior_vertices = 0;          ///< vertices not on a free (boundary) edge
  int irregular_interior = 0;         ///< interior vertices with valence (incident edges) != 4
  ShapeStats physical;
  bool has_frame = false;
  ShapeStats metric;
  EdgeLengthStats metric_edges;
  FrameStats frame;
};

/// Shape statistics of all cells of m, each mapped by M[c] when M is not empty (#cells
/// matrices), else in physical space.
ShapeStats shape_stats(const Mesh& m, const std::vector<Eigen::Matrix2d>& M = {});

/// Interior vertices (not on a free edge) and those of them whose valence is not 4.
void vertex_regularity(const Mesh& m, int& interior, int& irregular);

/// All figures. `frame` may be null; `frame_path` names it in messages and in the report.
QualityReport measure_quality(const Mesh& m, const Frame* frame = nullptr, const std::string& frame_path = "");

/// The report as JSON (the keys documented in docs/meshquality.md).
nlohmann::json to_json(const QualityReport& r);

}  // namespace quadapt
