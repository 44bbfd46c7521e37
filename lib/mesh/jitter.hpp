#pragma once
// Random perturbation of a mesh's interior nodes: a second, third, ... start mesh for an
// adaptive loop (the loop must not depend on its start mesh; docs/loop.md, START_JITTER).
#include <cstdint>

#include "mesh/mesh.hpp"

namespace quadapt {

struct JitterOptions {
  /// Largest move, as a fraction of the node's shortest incident edge (in (0, 0.45]).
  double fraction = 0.2;
  /// Seed of the moves (std::mt19937_64; the same seed gives the same moves on every platform).
  std::uint64_t seed = 1;
};

/// Moves every interior node of m (a node on no free edge: boundary nodes and the hanging nodes
/// of 2:1 meshes stay) to a point drawn uniformly from the disk of radius fraction * h around
/// it, h = its shortest incident edge in the unmoved mesh; nodes in index order, one angle and
/// one radius draw each. Cells and boundary are kept; every field is cleared (they belong to the
/// unmoved geometry). Returns the number of nodes moved. Throws InputError (naming `file`) for a
/// curved mesh, a fraction outside (0, 0.45], or when a moved cell has a corner with
/// non-positive cross product (inverted or non-convex: take a smaller fraction).
int jitter_interior_nodes(Mesh& m, const JitterOptions& opt, const std::string& file = "");

}  // namespace quadapt
