#pragma once
// Small conforming-mesh utilities used by the quad module (recombine, split, smoothing).
#include <array>
#include <string>
#include <vector>

#include "mesh/boundary.hpp"
#include "mesh/triangulation.hpp"
#include "mesh/mesh.hpp"

namespace quadapt {

/// The free edges chained into closed loops of node indices (first node not repeated). Loops
/// follow the free-edge orientation; the outer boundary of a CCW mesh has positive signed
/// area, holes negative. Throws InputError for a boundary that does not close into simple
/// loops (a node with more than one outgoing free edge).
std::vector<std::vector<int>> boundary_loops(const Mesh& m);

/// Refuses an input whose boundary is pinched — a node on more than two free edges (cells that
/// meet only there), which BAMG and the LpCVT triangulation cannot mesh: InputError "SOURCE: the
/// domain is pinched: the boundary node at (x, y) is on more than two boundary edges ...".
/// They failed later, naming "mesh" or their own output. Hanging nodes are no pinch.
void check_simple_boundary(const Mesh& m, const std::string& source);

/// Signed area of a closed polygon given by node indices.
double polygon_area(const Mesh& m, const std::vector<int>& loop);

/// Reverses every cell of negative signed area (fixing global orientation). Returns how many.
int orient_counter_clockwise(Mesh& m);

/// If m (all triangles) has an odd number of cells, splits the boundary triangle with the
/// longest free edge at that edge's midpoint (two triangles; the boundary edge, if listed in
/// m.boundary, becomes two edges of the same group). Returns true when a split was made.
bool make_triangle_count_even(Mesh& m);


}  // namespace quadapt
