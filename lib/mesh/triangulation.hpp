#pragma once
// Checks of a triangle mesh: the counts of lpcvt's output check, and the input check of
// recombine that throws the first problem.
#include <string>

#include "mesh/mesh.hpp"

namespace quadapt {

/// Validity of a triangulation: all triangles counter-clockwise with positive area, total area,
/// every boundary edge an edge of exactly one triangle, and every edge used by one triangle
/// only a boundary edge (the mesh conforms to its boundary).
struct TriangulationCheck {
  int triangles = 0;
  int non_positive = 0;          ///< triangles with area <= 0
  double min_area = 0;
  double area = 0;
  int boundary_edges = 0;
  int boundary_edges_missing = 0;  ///< boundary edges not an edge of exactly one triangle
  int free_edges_unlisted = 0;     ///< triangle edges on one triangle that are no boundary edge
  bool ok() const { return triangles > 0 && non_positive == 0 && boundary_edges_missing == 0 && free_edges_unlisted == 0; }
  std::string summary() const;
};
TriangulationCheck check_triangulation(const Mesh& tri);

/// Throws InputError("PATH: ...") unless m is a valid triangulation for recombination: at
/// least one cell, triangles only, finite coordinates, every cell counter-clockwise with
/// positive area, every listed boundary edge a free edge.
void require_triangulation(const Mesh& m, const std::string& path);

}  // namespace quadapt
