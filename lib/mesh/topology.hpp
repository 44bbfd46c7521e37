#pragma once
// Face connectivity of a (possibly non-conforming) mesh: the faces a DG method integrates over.
//
// A Face is a straight segment [a, b] shared by two cells (interior) or lying on the boundary.
// Conforming meshes: a face is a whole edge of both cells. Non-conforming 2:1 meshes (hanging
// nodes): a coarse cell's edge is split at the hanging node into two faces, each a whole edge
// of a fine cell and half an edge of the coarse cell.
//
// Each side k (0, 1) records its cell, its local edge e (from v[e] to v[(e+1)%nv]) and the edge
// parameters s_a[k], s_b[k] in [0, 1] of the face's end points a and b along that edge
// (s = 0 at v[e], s = 1 at v[e+1]). Side 0's edge runs from a to b (s_a[0] < s_b[0]); side 1,
// the neighbour, runs the other way (s_a[1] > s_b[1]). normal is side 0's outward unit normal.
#include <array>
#include <vector>

#include "mesh/mesh.hpp"

namespace quadapt {

struct Face {
  std::array<int, 2> cell{{-1, -1}};        ///< cell[1] = -1 on the boundary
  std::array<int, 2> local_edge{{-1, -1}};
  std::array<double, 2> s_a{{0, 0}};
  std::array<double, 2> s_b{{1, 1}};
  Vec2 a, b;                                ///< physical end points (side 0's orientation)
  Vec2 normal;                              ///< unit outward normal of side 0
  double length = 0;
  int group = -1;                           ///< boundary group index (boundary faces), else -1
  bool is_boundary() const { return cell[1] < 0; }
  bool is_conforming() const { return s_a[0] == 0 && s_b[0] == 1 && (cell[1] < 0 || (s_a[1] == 1 && s_b[1] == 0)); }
};

struct Topology {
  std::vector<Face> faces;
  std::vector<std::vector<int>> cell_faces;  ///< #cells lists of face indices touching each cell
  /// Face-neighbour cells of c (each once, conforming or not).
  std::vector<int> neighbours(int c) const;
};

/// Builds the faces. Boundary faces get the group of the matching Mesh::boundary edge (-1 if none).
/// Throws InputError("mesh: ...") for an edge shared by more than two cells or a non-conforming
/// configuration other than 2:1 (an edge matched by neither a neighbour edge, the two halves of
/// a hanging-node split, nor the boundary is reported as a boundary face).
Topology build_topology(const Mesh& m);

}  // namespace quadapt
