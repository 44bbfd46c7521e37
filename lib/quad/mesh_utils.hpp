#pragma once
// Small conforming-mesh utilities used by the quad module (recombine, split, smoothing).
#include <array>
#include <string>
#include <vector>

#include "mesh/mesh.hpp"

namespace quadapt {

/// Edges used by exactly one cell, oriented as in that cell (so the cell lies on their left
/// when cells are counter-clockwise), in cell order. Throws InputError("mesh: ...") for an
/// edge shared by more than two cells or used twice in the same direction (inconsistent
/// orientation / overlapping cells).
std::vector<std::array<int, 2>> free_edges(const Mesh& m);

/// The free edges chained into closed loops of node indices (first node not repeated). Loops
/// follow the free-edge orientation; the outer boundary of a CCW mesh has positive signed
/// area, holes negative. Throws InputError for a boundary that does not close into simple
/// loops (a node with more than one outgoing free edge).
std::vector<std::vector<int>> boundary_loops(const Mesh& m);

/// Signed area of a closed polygon given by node indices.
double polygon_area(const Mesh& m, const std::vector<int>& loop);

/// Flags of nodes lying on a free edge (boundary nodes; hanging nodes are on free edges too).
std::vector<char> boundary_node_flags(const Mesh& m);

/// Reverses every cell of negative signed area (fixing global orientation). Returns how many.
int orient_counter_clockwise(Mesh& m);

/// If m (all triangles) has an odd number of cells, splits the boundary triangle with the
/// longest free edge at that edge's midpoint (two triangles; the boundary edge, if listed in
/// m.boundary, becomes two edges of the same group). Returns true when a split was made.
bool make_triangle_count_even(Mesh& m);

/// Throws InputError("PATH: ...") unless m is a valid triangulation for recombination: at
/// least one cell, triangles only, finite coordinates, every cell counter-clockwise with
/// positive area, every listed boundary edge a free edge.
void check_triangulation(const Mesh& m, const std::string& path);

}  // namespace quadapt
