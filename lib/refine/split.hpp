#pragma once
// Isotropic split of flagged quads into 4 children, hanging nodes kept (thesis §2.5).
//
// A flagged quad v0 v1 v2 v3 gets one node per edge and one at its centre, the bilinear image of
// the reference point (0, 0) (= the mean of the four vertices). Edge nodes are:
//   - the existing hanging node on a COARSE edge (the neighbour is already finer: the node is
//     reused and stops hanging, the edge becomes two conforming faces);
//   - otherwise the edge midpoint, created once and shared with the neighbour when the neighbour
//     is split too (if not, it becomes a hanging node of the neighbour: a legal 2:1 face).
// Children, counter-clockwise like the parent and in the parent's reference quadrants
// [-1,0]x[-1,0], [0,1]x[-1,0], [0,1]x[0,1], [-1,0]x[0,1]:
//   (v0, m0, c, m3), (m0, v1, m1, c), (c, m1, v2, m2), (m3, c, m2, v3)
// with m_e on local edge e. The children take the parent's place in the cell order; unflagged
// cells keep their order and vertices. Node order: old nodes unchanged, then new nodes in the
// order the flagged cells are visited (edge nodes e = 0..3, then the centre) — deterministic.
//
// Boundary edges of split cells become two boundary edges in the same group, so every group's
// total length is unchanged. Fields: the output has none (they describe the old mesh), except
// that with keep_scalar_fields every 1-component CellField is copied from each parent to its
// four children (piecewise-constant injection; multi-component and cell-node fields such as
// "u" and "Vinv" are dropped).
#include <vector>

#include "mesh/mesh.hpp"
#include "refine/cell_edges.hpp"

namespace quadapt {

/// Splits the flagged quads of m. `edges` = classify_cell_edges(m, build_topology(m)),
/// `flags` #cells (nonzero = split) must be balanced (refine/balance.hpp): throws Error otherwise,
/// and InputError("mesh: ...") when a flagged cell is not a quad.
Mesh split_cells(const Mesh& m, const CellEdges& edges, const std::vector<char>& flags,
                 bool keep_scalar_fields = false);

}  // namespace quadapt
