#pragma once
// Boundary edges lying on other boundary edges: the trace of two blocks whose shared nodes were
// not merged (Gmsh without Coherence Mesh;, or with a slip of 1e-9 .. 1e-3 between the blocks).
// Such a mesh is valid — a domain with a slit, which a crack legitimately is — so this is a
// warning for the tools to print, never an error (docs/file-formats.md, "Boundary groups").
//
// Criterion. Two free edges e and f (edges of one cell, each oriented as in its cell, i.e. with
// the domain on its left for counter-clockwise cells; the straight chord between its two
// vertices, also for curved cells) lie on each other when
//   1. they share no node;
//   2. they run in opposite directions within 30 degrees: t_e . t_f < -cos(30 deg) for their
//      unit tangents (the two faces of a slit run opposite ways; two consecutive edges of one
//      side, or of two blocks' common outer side, run the same way);
//   3. with tol = 1e-2 x the length of the shorter of the two (mesh length units), the shorter
//      edge's projection on the longer edge overlaps that edge over more than tol, and over that
//      overlap the shorter edge is at most tol from the longer edge's line. That largest
//      distance is the pair's gap (mesh length units).
// Matching halves (the same nodes on both sides, moved apart) and non-matching ones (a
// T-junction: blocks 2 and 3 cells tall side by side, a node of one side near the interior of
// an edge of the other) are both found; a channel whose width is more than 1% of its edges'
// length is not. Pairs closer than 1e-9 x the edge length along one line are refused before by
// validate_mesh (cells meeting without sharing an edge).
//
// Cost: linear in the cells to find the free edges (a counting sort by node, no hash map and no
// build_topology), then O(n log n) in the number n of free edges (candidate pairs from a grid per
// power of 2 of the edge length, so that graded boundaries stay near-linear). A 1e5-cell mesh:
// a few ms, against ~0.2 s to read it.
#include <string>
#include <vector>

#include "mesh/boundary.hpp"
#include "mesh/mesh.hpp"

namespace quadapt {

/// Two free edges lying on each other: indices into the edge list given, e < f, and their gap
/// (mesh length units).
struct EdgeOverlap {
  int e = -1, f = -1;
  double gap = 0;
};

/// The pairs of `edges` (free edges oriented as in their cells, e.g. boundary_free_edges) that
/// lie on each other by the criterion above, ordered by (e, f). Edges of zero or non-finite length are ignored.
std::vector<EdgeOverlap> overlapping_edges(const Mesh& m, const std::vector<EdgeNodes>& edges);

/// The warnings about m's boundary that do not refuse it: at most one line, when free edges lie
/// on each other ("N boundary edges lie on other boundary edges (P pairs, at most G apart;
/// first: ...): ..." naming the fix). Empty when there is nothing to say. Never throws for a
/// mesh that validate_mesh accepts (node indices in range are required).
std::vector<std::string> boundary_warnings(const Mesh& m);

}  // namespace quadapt
