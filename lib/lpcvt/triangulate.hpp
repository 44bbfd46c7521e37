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
#include "mesh/triangulation.hpp"

namespace quadapt::lpcvt {

/// `sites[0..nfixed)` are the boundary sites; `segments` (pairs of boundary sites) with their
/// `segment_group` (index into background.groups). Free sites lying on a segment (within
/// rounding) are dropped. Sites not used by any kept triangle are not written. Throws
/// NumericalError when the boundary segments intersect each other.
Mesh triangulate_domain(const std::vector<Vec2>& sites, int nfixed,
                        const std::vector<std::array<int, 2>>& segments,
                        const std::vector<int>& segment_group, const Mesh& background);


}  // namespace quadapt::lpcvt
