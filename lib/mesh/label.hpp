#pragma once
// How messages name mesh entities. Cells and nodes are numbered from 1 in file order — the
// element and node tags of the files quadapt writes (io/msh_write.cpp writes tag = index + 1),
// and Gmsh's own numbering — so a number in a message can be looked up in the file.
#include <string>

#include "mesh/mesh.hpp"

namespace quadapt {

/// 1-based number of the cell or node with 0-based index i, as text: "i + 1".
std::string number_text(long long i);

/// "(x, y)": a point in messages (6 significant digits).
std::string point_text(const Vec2& p);

/// "cell N (centroid (x, y))": cell c of m (0-based index), numbered from 1.
std::string cell_label(const Mesh& m, int c);

}  // namespace quadapt
