#pragma once
// Final output of the L_p-CVT generator (thesis §4.6): the constrained Delaunay triangulation
// (CGAL Constrained_Delaunay_triangulation_2) of the sites with the boundary segments as
// constraints; only the triangles inside the domain are kept (odd nesting depth, counted from
// the infinite face across constraints: holes and re-entrant corners are excluded). The result
// is a triangle Mesh (counter-clockwise) with the boundary segments as 2-node boundary edges in
// their groups (names and tags of the background mesh), oriented with the domain on their left.
#include <array>
#include <string>
#include <vector>

#include "mesh/mesh.hpp"

namespace quadapt::lpcvt {

/// `sites[0..nfixed)` are the boundary sites; `segments` (pairs of boundary sites) with their
/// `segment_group` (index into background.groups). Free sites lying on a segment (within
/// rounding) are dropped. Sites not used by any kept triangle are not written. Throws
/// NumericalError when the boundary segments intersect each other.
Mesh triangulate_domain(const std::vector<Vec2>& sites, int nfixed,
                        const std::vector<std::array<int, 2>>& segments,
                        const std::vector<int>& segment_group, const Mesh& background);

/// Validity of a triangulation: all triangles counter-clockwise with positive area, total area,
/// every boundary edge an edge of exactly one triangle, and every edge used by one triangle
/// only a boundary edge (the mesh conforms to its boundary).
struct TriangulationCheck {
  int triangles = 0;
  int non_positive = 0;          ///< triangles with area <= 0
  double min_area = 0;
  double area = 0;
  int boundary_edges = 0;
  int boundary_edges_missing = 0;  ///< boundary edges not an edge of exactly one triangle
  int free_edges_unlisted = 0;     ///< triangle edges on one triangle that are no boundary edge
  bool ok() const { return triangles > 0 && non_positive == 0 && boundary_edges_missing == 0 && free_edges_unlisted == 0; }
  std::string summary() const;
};
TriangulationCheck check_triangulation(const Mesh& tri);

}  // namespace quadapt::lpcvt
