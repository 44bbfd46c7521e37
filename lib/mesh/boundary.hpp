#pragma once
// The boundary of a mesh from its free edges, split into named curves (docs/design.md §3).
//
// Files without boundary lines (PHiLiP's frame files) or with boundary lines on only part of
// the boundary get the missing boundary from the mesh itself: the free edges (edges of exactly
// one cell; the coarse edge and the two halves of a 2:1 hanging-node split are interior) are
// chained into loops, each loop is split into curves at corners, and each curve becomes a
// boundary group. A node is a corner when the boundary turns there by more than
// `corner_angle_deg`, or when it turns at all and one of the two straight runs meeting there
// has at least two collinear edges (the supporting line of a polygon side changes; a finely
// discretised smooth curve, whose every node turns a little, is not split).
// Naming: when the domain is the unit square [0,1]^2 a curve lying on one side is called
// bottom (y = 0), right (x = 1), top (y = 1) or left (x = 0); otherwise (or when that name is
// taken) boundary_1, boundary_2, ... in a deterministic order: loops by their lowest (y, then
// x) node, curves along each loop (counter-clockwise around the domain) from its lowest corner.
#include <array>
#include <cstdint>
#include <string>
#include <string>
#include <vector>

#include "mesh/label.hpp"
#include "mesh/mesh.hpp"

namespace quadapt {

using EdgeNodes = std::array<int, 2>;

/// Keys of the directed edge a -> b and of the undirected edge {a, b} (maps of edges).
std::uint64_t directed_edge_key(int a, int b);
std::uint64_t edge_key(int a, int b);

/// Flags (#nodes) of the nodes lying on a free edge — an edge of one cell only: boundary nodes,
/// and the hanging nodes of 2:1 meshes (their half-edges are used once) — or on a boundary edge.
std::vector<char> boundary_node_flags(const Mesh& m);

/// Edges used by exactly one cell (conforming meshes: a hanging node's long edge counts as
/// free), oriented as in that cell (the cell on their left when cells are counter-clockwise),
/// in cell order. strict: throws InputError("mesh: ...") for an edge shared by more than two
/// cells or used twice in the same direction (inconsistent orientation / overlapping cells).
std::vector<EdgeNodes> free_edges(const Mesh& m, bool strict = true);

/// Free edges, each oriented as its (counter-clockwise) cell runs it, i.e. with the domain on
/// the left. Uses build_topology (hanging nodes); if the topology cannot be built (overlapping
/// or misoriented cells, which validate_mesh reports), every edge used by one cell only.
std::vector<EdgeNodes> boundary_free_edges(const Mesh& m);

/// True when the cells tile the unit square: the cells' nodes span [0,1]^2 and the total
/// area is 1 (both within `tol`).
bool is_unit_square(const Mesh& m, double tol = 1e-9);

/// Side of the unit square holding the segment a-b: "bottom", "right", "top", "left", or "".
std::string unit_square_side(const Vec2& a, const Vec2& b, double tol = 1e-9);

struct BoundaryOptions {
  double corner_angle_deg = 30;  ///< a turn larger than this is a corner
};

/// Chains oriented `edges` into loops (or open chains) and splits them at corners. Returns, per
/// curve, the indices into `edges` in chain order; curves in the deterministic order above.
std::vector<std::vector<int>> split_into_curves(const Mesh& m, const std::vector<EdgeNodes>& edges,
                                                const BoundaryOptions& opt = {});

/// Adds every free edge that no Mesh::boundary edge covers to new boundary groups, one per
/// curve, named as above (names already in use are skipped; new tags follow the largest
/// existing group tag). Returns the number of edges added (0 when the boundary was complete).
int complete_boundary(Mesh& m, const BoundaryOptions& opt = {});

}  // namespace quadapt
