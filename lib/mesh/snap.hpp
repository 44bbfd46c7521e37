#pragma once
// Boundary nodes onto the true curves (docs/curved.md, "Geometry"): a straight-sided mesh made on a
// polygon of the domain (BAMG's, refine's new mid-edge nodes, recombine's split points) gets its
// boundary nodes projected onto the geometry's curves of the same name.
#include <string>
#include <vector>

#include "mesh/geometry.hpp"
#include "mesh/mesh.hpp"

namespace quadapt {

struct SnapStats {
  int boundary_nodes = 0;   ///< nodes of boundary edges
  int moved = 0;            ///< nodes that moved (by more than 0)
  double max_move = 0;      ///< largest distance moved
  double max_distance = 0;  ///< after snapping: largest distance of a boundary node to its curve
  double max_interior_move = 0;  ///< largest move of an interior node (the blend)
  /// A boundary group none of whose nodes lay on its curves before the snap, moved by more than
  /// 5 % of the shortest boundary edge somewhere: a mesh of G's domain has its polygon's vertices
  /// on the curves (the start mesh, the frame's polygon that BAMG keeps, refine's old nodes), a mesh
  /// of another domain (the annulus scaled by 1.1: every node moved, by up to 26 % of an edge) has
  /// none. One message per such group (the tools warn with it).
  std::vector<std::string> warnings;
};

/// The geometry's curves of each boundary group of m (by name). Throws InputError(path, ...)
/// naming a group that is not a physical curve of g.
std::vector<std::vector<int>> group_curves(const Mesh& m, const BoundaryGeometry& g, const std::string& path);

/// Moves every node of m's boundary edges to the closest point of the curves named like its
/// group (a node of two groups: of either, the closer). With `move_interior`, the interior
/// follows by the first of these that inverts no cell: (1) the centre C of every split parent
/// (a mid-edge boundary node M whose two cells share one interior vertex C of valence 4, or 3
/// for a triangle split into 3 quads) moves by 1/2 (2/3) of M's move — the parent's
/// transfinite map at its centre; (2) nothing; (3) every interior node x by the blend of the
/// boundary moves d_v:
///     D(x) = sum_v phi(|x - x_v| / rho_v) d_v / max(1, sum_v phi(|x - x_v| / rho_v)),
/// rho_v the shortest boundary edge at v, phi Wendland's C2 function (curve_boundary.hpp): a
/// thin boundary-layer cell above a node that moves by more than its height moves along
/// instead of folding. (Off for meshes with hanging nodes, which must stay on their edges.)
/// Straight-sided meshes only. Throws
/// InputError(path, ...) when a group has no curve in g or a node lies farther from its curves
/// than half its shortest boundary edge (the mesh is not a mesh of g's domain), NumericalError
/// when a moved node inverts a cell (named).
SnapStats snap_to_geometry(Mesh& m, const BoundaryGeometry& g, const std::string& path, bool move_interior = true);

/// Wendland's C2 function (1 - r)^4 (4 r + 1) on [0, 1), 0 beyond: the blends' weight.
double wendland_c2(double r);

}  // namespace quadapt
