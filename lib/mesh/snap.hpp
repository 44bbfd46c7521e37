#pragma once
// Boundary nodes onto the true curves (docs/curved.md, "Geometry"): a straight-sided mesh made on a
// polygon of the domain (BAMG's, refine's new mid-edge nodes, recombine's split points) gets its
// boundary nodes projected onto the geometry's curves of the same name.
#include <string>

#include "mesh/geometry.hpp"
#include "mesh/mesh.hpp"

namespace quadapt {

struct SnapStats {
  int boundary_nodes = 0;   ///< nodes of boundary edges
  int moved = 0;            ///< nodes that moved (by more than 0)
  double max_move = 0;      ///< largest distance moved
  double max_distance = 0;  ///< after snapping: largest distance of a boundary node to its curve
};

/// The geometry's curves of each boundary group of m (by name). Throws InputError(path, ...)
/// naming a group that is not a physical curve of g.
std::vector<std::vector<int>> group_curves(const Mesh& m, const BoundaryGeometry& g, const std::string& path);

/// Moves every node of m's boundary edges to the closest point of the curves named like its
/// group (a node of two groups: of either, the closer). Straight-sided meshes only. Throws
/// InputError(path, ...) when a group has no curve in g or a node lies farther from its curves
/// than half its shortest boundary edge (the mesh is not a mesh of g's domain), NumericalError
/// when a moved node inverts a cell (named).
SnapStats snap_to_geometry(Mesh& m, const BoundaryGeometry& g, const std::string& path);

}  // namespace quadapt
