#pragma once
// A numbering of a mesh that depends only on its geometry: renumbering a file's nodes or cells,
// or starting a cell's vertex list at another corner, gives the same canonical mesh. The tools
// that read a frame (frame/frame.hpp read_frame) work on it, so their outputs do not depend on
// how the frame's file happens to number its background (docs/file-formats.md, "Frame files").
//
// The order:
//  - nodes by (x, y), lexicographically (exact doubles; equal points keep their file order);
//  - cells by their sorted list of new node indices (triangles sort before quads sharing the
//    same first three); distinct valid cells never share the whole list;
//  - each cell's vertex list rotated to start at its smallest new node index, keeping the
//    counter-clockwise order — only for straight-sided cells without per-cell-node fields
//    (a curved cell's control points and a CellNodeField's values are laid out on the cell's
//    reference square; those cells keep their first vertex);
//  - boundary edges by (group, smaller node, larger node), each edge keeping its direction.
// Cell fields, per-cell-node fields and curved control points move with their cells; the
// boundary groups, names, tags and the frame convention are unchanged.
#include <vector>

#include "mesh/mesh.hpp"

namespace quadapt {

/// How canonical_order renumbered: new_node[old node] and old_cell[new cell].
struct Renumbering {
  std::vector<int> new_node;
  std::vector<int> old_cell;
};

/// The mesh in its canonical order (above); `r` (optional) receives the permutations.
Mesh canonical_order(const Mesh& m, Renumbering* r = nullptr);

}  // namespace quadapt
