#pragma once
// Shape measures of one straight-sided cell given by its vertex positions (counter-clockwise),
// in whatever space the positions live: physical space, or the metric space of a frame
// (positions mapped by M = V^-1). docs/meshquality.md states the definitions:
//  - interior angle at corner i: from edge (p_i -> p_i+1) counter-clockwise to edge
//    (p_i -> p_i-1), degrees in [0, 360); > 180 at a reflex or inverted corner.
//  - scaled Jacobian at corner i: cross(e_next, e_prev) / (|e_next| |e_prev|) = sin(angle), in
//    [-1, 1]; for a quad this is the normalised Jacobian determinant of the bilinear map at that
//    corner. Triangles: times 2/sqrt(3), clamped to [-1, 1], so the equilateral triangle has 1.
//    The cell's scaled Jacobian is the minimum over its corners.
//  - edge ratio: longest / shortest edge; orientation: direction of the longest edge, degrees
//    in [0, 180).
#include <vector>

#include "mesh/mesh.hpp"

namespace quadapt {

struct CellShape {
  int nv = 4;
  double angle_deg[4] = {0, 0, 0, 0};
  double scaled_jacobian = 0;   ///< minimum over the corners
  double edge_min = 0, edge_max = 0;
  double orientation_deg = 0;   ///< direction of the longest edge in [0, 180)
  double edge_ratio() const { return edge_min > 0 ? edge_max / edge_min : INFINITY; }
};

/// Measures of the polygon p[0..nv-1] (nv = 3 or 4).
CellShape cell_shape(const Vec2* p, int nv);

/// Measures of curved quad c of m (geometric order q >= 2, mesh/curved.hpp), its control points
/// optionally mapped by M (y = M x; the map of the mapped points is M times the cell's map):
///  - angle at a corner: between the two curved edges' tangents there (the map's Jacobian
///    columns), as for a straight cell;
///  - scaled Jacobian: the minimum of det J / (|dx/dxi| |dx/deta|) over the (2q+2)^2
///    equispaced points of the reference square, corners included (at a corner this is the
///    straight definition's sin(angle); inside it sees a curved edge that bends the cell);
///  - edge lengths: arc lengths of the curved edges (8-point Gauss); orientation: the direction
///    of the longest edge's chord.
CellShape curved_cell_shape(const Mesh& m, int c, const Eigen::Matrix2d* M = nullptr);

/// Arc length of local edge e of cell c of a curved mesh, its points mapped by M (y = M x)
/// when M is not null; 8-point Gauss quadrature of |dx/ds| (exact to ~1e-12 for q <= 6 at the
/// cell sizes of adaptation).
double curved_edge_length(const Mesh& m, int c, int e, const Eigen::Matrix2d* M = nullptr);

/// Vertex positions of cell c, optionally mapped by the 2x2 matrix M (y = M x).
void cell_points(const Mesh& m, int c, Vec2 out[4]);
void cell_points(const Mesh& m, int c, const Eigen::Matrix2d& M, Vec2 out[4]);

/// Median (average of the two middle values for an even count); 0 for an empty set.
double median(std::vector<double> v);

/// Median of axial directions (degrees, period 180): the angles are unwrapped into a
/// 180-degree window centred on their circular mean (of the doubled angles) before the median
/// is taken, so a cluster around 0/180 gives a median near 0 or 180, not 90. Result in [0, 180).
double axial_median_deg(const std::vector<double>& angles_deg);

}  // namespace quadapt
