#pragma once
// Blossom-Quad recombination of a triangulation through the Gmsh SDK (thesis §4.6, [110]).
//
// The triangulation (counter-clockwise triangles, boundary = its free edges) is handed to
// Gmsh as a built-in ("geo") plane surface: one geo point per boundary node, one geo line per
// boundary edge, one curve loop per boundary loop (outer first), the nodes and triangles
// injected as that surface's mesh with parametric coordinates (a discrete surface gave
// flipped, overlapping elements here: docs/design.md §6). Then
// Mesh.RecombinationAlgorithm = 1 (Blossom: minimum-cost perfect matching of the triangles'
// dual graph, cost = deviation of the quad's angles from 90 degrees in physical space) and
// Gmsh's model::mesh::recombine() (through lib/gmsh/gmsh_recombine.hpp).
//
// Two ways of using Gmsh's answer:
//  - Pairing (also the fall-back of the clean-up mode): Gmsh runs without its clean-up (Mesh.RecombineOptimizeTopology = 0,
//    Mesh.Smoothing = 0) and only its matching is used: each returned quad is mapped back to
//    the two input triangles it joins (by node identity), and accepted when they are adjacent,
//    still unpaired and form a strictly convex quad (every corner's scaled Jacobian >=
//    min_pair_jacobian). Gmsh leaves triangles unmatched when their pair's physical-space
//    quality is below its threshold (common on anisotropic meshes): adjacent left-overs are
//    then paired greedily (best corner scaled Jacobian first, same convexity rule); every
//    other input triangle stays a triangle. The result is exactly a
//    pairing of the input, so it cannot overlap, keeps every node where it was (anisotropy is
//    preserved) and has quads + triangles/2 = input triangles / 2 (predictable complexity).
//    Gmsh 4.8's raw Blossom output was seen to contain a few clockwise triangles overlapping
//    their neighbours on anisotropic BAMG meshes; the pairing never uses those.
//  - Gmsh clean-up (gmsh_cleanup = true, the default): Gmsh's own topology optimisation and node
//    relocation run, and its mesh is taken as it is after checks: every cell is re-oriented
//    counter-clockwise, the cell areas must add up to the input's area (no overlap), the free
//    edges must be exactly the input's boundary edges and no cell may be inverted. When a check
//    fails, the pairing is used instead (stats.fell_back, stats.fallback_reason).
//
// Blossom needs an even number of triangles, otherwise Gmsh silently falls back to greedy
// matching: the caller (recombine_to_all_quads) makes the count even first.
// Gmsh's own errors (std::string throws, logged errors) become ExternalError.
#include <string>

#include "mesh/mesh.hpp"

namespace quadapt {

struct BlossomOptions {
  int algorithm = 1;               ///< Mesh.RecombinationAlgorithm: 0 simple (greedy), 1 Blossom
  bool gmsh_cleanup = true;        ///< take Gmsh's cleaned-up mesh (see above); false: the pairing
  int optimize_topology = 5;       ///< clean-up only: Mesh.RecombineOptimizeTopology passes
  int smoothing = 1;               ///< clean-up only: Mesh.Smoothing passes of node relocation
  double min_pair_jacobian = 0.01; ///< pairing: smallest corner scaled Jacobian of an accepted quad
};

struct BlossomStats {
  int triangles_in = 0;      ///< triangles handed to Gmsh
  int quads = 0;             ///< quads after recombination
  int triangles = 0;         ///< triangles left after recombination
  int gmsh_quads = 0;        ///< quads in Gmsh's answer
  int rejected_pairs = 0;    ///< pairing: Gmsh quads not used (not a valid convex pair)
  int greedy_pairs = 0;      ///< pairing: left-over neighbours paired after Gmsh's matching
  int reoriented = 0;        ///< clean-up: cells Gmsh returned clockwise (reversed)
  bool fell_back = false;    ///< clean-up failed its checks; the pairing was used
  std::string fallback_reason;
};

/// Recombines the all-triangle, counter-clockwise, conforming mesh `tri` into a quad-dominant
/// mesh with the same boundary (boundary edges and groups carried over). Fields are dropped.
Mesh blossom_recombine(const Mesh& tri, const BlossomOptions& opt = {}, BlossomStats* stats = nullptr);

}  // namespace quadapt
