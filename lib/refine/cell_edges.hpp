#pragma once
// Per-cell-edge view of a (possibly non-conforming, 2:1) quad mesh, derived from the face list of
// mesh/topology.hpp. Refinement needs to know, for every local edge of every cell, whether the
// edge is
//   - on the boundary,
//   - conforming (shared whole with one neighbour),
//   - COARSE: split by a hanging node into two faces, each a whole edge of a finer neighbour
//     (the node is reused as the edge's midpoint when the cell is split), or
//   - FINE: half of a coarser neighbour's edge (splitting this cell alone would put four faces
//     along the neighbour's edge, a 4:1 configuration; thesis Fig. 2.2 forbids it).
// Files carry no refinement levels: this classification IS the level information, read off the
// geometry (the edge parameters s_a, s_b of the faces).
#include <array>
#include <vector>

#include "mesh/mesh.hpp"
#include "mesh/topology.hpp"

namespace quadapt {

enum class EdgeKind { Boundary, Conforming, Coarse, Fine };

/// One local edge e of a cell (from v[e] to v[(e+1) % nv]).
struct CellEdge {
  EdgeKind kind = EdgeKind::Boundary;
  /// Conforming / Fine: the neighbour across (for Fine: the coarser cell). Coarse: the two finer
  /// neighbours in edge order (from v[e] towards v[e+1]). -1 where absent.
  std::array<int, 2> neighbour{{-1, -1}};
  /// Coarse: the hanging node on this edge (node index); else -1.
  int hanging_node = -1;
};

/// edges[c][e] for every cell c and local edge e < cells[c].nv.
using CellEdges = std::vector<std::array<CellEdge, 4>>;

/// Classifies every cell edge from the faces of `t` = build_topology(m).
/// Throws InputError("mesh: ...") when a cell edge is covered by more than two faces, or when two
/// free (boundary-kind) edges overlap: a non-conformity other than 2:1, e.g. four fine faces along
/// one coarse edge, which build_topology leaves as unmatched "boundary" faces.
CellEdges classify_cell_edges(const Mesh& m, const Topology& t);

/// Number of hanging nodes of the mesh: the number of coarse edges (each holds exactly one).
int count_hanging_nodes(const Mesh& m, const Topology& t);
int count_hanging_nodes(const Mesh& m);

}  // namespace quadapt
