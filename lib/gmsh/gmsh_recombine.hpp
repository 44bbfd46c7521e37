#pragma once
// Gmsh's Blossom-Quad recombination of a given triangulation (gmsh::model::mesh::recombine),
// behind the SDK adapter: the only place that builds a Gmsh model. quad/blossom.cpp decides
// what to do with the answer.
#include <vector>

#include "mesh/mesh.hpp"

namespace quadapt {

struct GmshRecombineOptions {
  int algorithm = 1;          ///< Mesh.RecombinationAlgorithm (1 = Blossom)
  int optimize_topology = 0;  ///< Mesh.RecombineOptimizeTopology
  int smoothing = 0;          ///< Mesh.Smoothing (passes)
};

/// Gmsh's result: its nodes (the input's, possibly moved, plus any it added) and its cells
/// (triangles and quads, node indices into `nodes`).
struct GmshRecombined {
  std::vector<Vec2> nodes;
  std::vector<Cell> cells;
};

/// Recombines the triangles of `tri` (counter-clockwise) in one plane surface bounded by
/// `loops` (closed node loops, the outer one first); `on_boundary[v]` marks the loops' nodes.
/// Gmsh's global options are set for the call and restored afterwards (GmshOptionGuard).
/// Throws ExternalError when Gmsh fails or answers with an unexpected element.
GmshRecombined gmsh_recombine(const Mesh& tri, const std::vector<std::vector<int>>& loops,
                              const std::vector<char>& on_boundary, const GmshRecombineOptions& opt);

}  // namespace quadapt
