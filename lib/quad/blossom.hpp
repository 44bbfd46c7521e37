#pragma once
// Blossom-Quad recombination of a triangulation through the Gmsh SDK (thesis §4.6, [110]).
//
// The triangulation (counter-clockwise triangles, boundary = its free edges) is handed to
// Gmsh as a built-in ("geo") plane surface: one geo point per boundary node, one geo line per
// boundary edge, one curve loop per boundary loop (outer first), the nodes and triangles
// injected as that surface's mesh with parametric coordinates. This lets Gmsh's own clean-up
// (topology optimisation, node repositioning) run, which a discrete surface would not do
// (../shared/LIBRARY-FACTS.md). Then Mesh.RecombinationAlgorithm = 1 (Blossom: minimum-cost
// perfect matching of the triangles' dual graph, cost = deviation of the quad's angles from
// 90 degrees in physical space) and gmsh::model::mesh::recombine().
//
// Blossom needs an even number of triangles, otherwise Gmsh silently falls back to greedy
// matching: the caller (recombine_to_all_quads) makes the count even first.
//
// After Gmsh, every cell is re-oriented counter-clockwise and checked: the sum of the cell
// areas must equal the input's area (no overlap), the output's free edges must be exactly the
// input's boundary edges (boundary nodes are never moved), and no cell may be inverted. Any
// violation throws ExternalError; Gmsh's own errors (std::string throws) become ExternalError.
#include "mesh/mesh.hpp"

namespace quadapt {

struct BlossomOptions {
  int algorithm = 1;               ///< Mesh.RecombinationAlgorithm: 0 simple (greedy), 1 Blossom
  int optimize_topology = 5;       ///< Mesh.RecombineOptimizeTopology (passes; 0 = off)
  // Gmsh 4.8 always repositions interior nodes after recombining a surface that has a
  // parametrization, and uses a fixed minimum quality of 0.01 for a pair to become a quad.
};

struct BlossomStats {
  int triangles_in = 0;  ///< triangles handed to Gmsh
  int quads = 0;         ///< quads after recombination
  int triangles = 0;     ///< triangles left after recombination
  int reoriented = 0;    ///< cells Gmsh returned clockwise (reversed)
};

/// Recombines the all-triangle, counter-clockwise, conforming mesh `tri` into a quad-dominant
/// mesh with the same boundary (boundary edges and groups carried over). Fields are dropped.
Mesh blossom_recombine(const Mesh& tri, const BlossomOptions& opt = {}, BlossomStats* stats = nullptr);

}  // namespace quadapt
