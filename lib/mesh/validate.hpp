#pragma once
// Mesh validation with one-line, actionable errors. Tools call validate_mesh after reading.
#include <string>
#include <vector>

#include "mesh/mesh.hpp"

namespace quadapt {

enum class CellKind { Any, Quads, Triangles };

struct ValidateOptions {
  CellKind require = CellKind::Any;           ///< element type the tool needs
  bool allow_hanging_nodes = true;            ///< 2:1 non-conforming quads are legal
  std::vector<std::string> required_groups;   ///< boundary names that must exist (case's BCs)
  std::vector<std::string> required_fields;   ///< cell or cell-node fields that must exist
  bool allow_curved = false;                  ///< curved cells (Mesh::curved) are accepted

  /// Options requiring one cell kind (e.g. all quads).
  static ValidateOptions cells(CellKind kind) {
    ValidateOptions v;
    v.require = kind;
    return v;
  }
  /// Options requiring the named fields (e.g. {"Vinv"} for a frame file).
  static ValidateOptions fields(std::vector<std::string> names) {
    ValidateOptions v;
    v.required_fields = std::move(names);
    return v;
  }
};

/// What validate_mesh finds wrong with the shape of cell c ("inverted: ...", "non-convex: ...",
/// "degenerate: zero Jacobian at corner 1 (0.5, 0.38) (vertices in line)", ...), or "" when it
/// accepts it. For code that makes cells (recombine), so that it never writes one that every tool
/// reading it refuses.
std::string cell_shape_problem(const Mesh& m, int c);

/// Throws InputError("PATH: problem") on: no cells; a cell type other than required; a
/// non-finite coordinate; a node index out of range; an inverted (negative Jacobian at a corner)
/// or degenerate (zero area) cell, naming the cell and its centroid; a boundary edge that is not
/// a free edge of the mesh; a required boundary group or field missing (listing what exists);
/// a field whose length does not match the cell count; a field value that is NaN or infinite;
/// curved cells when the tool does not accept them (allow_curved), else control points that do
/// not match the cells or a curved cell whose sampled Jacobian is not positive
/// (mesh/curved.hpp min_scaled_jacobian).
void validate_mesh(const Mesh& m, const std::string& path, const ValidateOptions& opt = {});

}  // namespace quadapt
