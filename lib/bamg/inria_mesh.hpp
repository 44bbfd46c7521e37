#pragma once
// The INRIA ".mesh" format (MeshVersionFormatted 1, Dimension 2) that BAMG reads and writes,
// and BAMG's ".mtr" metric file. Only what the bamgquad path needs:
//   Vertices  (x y ref), Edges (v1 v2 ref), Triangles (v1 v2 v3 ref), Corners (v),
//   RequiredVertices (v); indices are 1-based in the file, 0-based here. Other sections are
//   skipped on reading (Geometry, Identifier, SubDomain, VertexOnGeometric..., ...).
// Metric file (BAMG's "-M" file): first line "NV 3", then per vertex "m11 m12 m22" — the
// symmetric tensor 𝓜 = [[m11, m12], [m12, m22]] whose unit ball is the target element
// (edge e has length sqrt(e^T 𝓜 e) in the metric; BAMG aims at length 1).
#include <Eigen/Core>
#include <array>
#include <iosfwd>
#include <string>
#include <vector>

#include "mesh/mesh.hpp"

namespace quadapt {

struct InriaMesh {
  std::vector<Vec2> vertices;
  std::vector<int> vertex_ref;                 ///< #vertices
  std::vector<std::array<int, 3>> edges;       ///< v1, v2, ref
  std::vector<std::array<int, 4>> triangles;   ///< v1, v2, v3, ref
  std::vector<int> corners;                    ///< vertex indices
  std::vector<int> required_vertices;          ///< vertex indices
};

/// Writes the mesh (17 significant digits). Throws ExternalError on a stream failure.
void write_inria_mesh(const InriaMesh& m, std::ostream& out);
void write_inria_mesh(const InriaMesh& m, const std::string& path);

/// Reads a 2D .mesh file. Throws InputError("PATH: problem") on a malformed file.
InriaMesh read_inria_mesh(std::istream& in, const std::string& path_for_messages);
InriaMesh read_inria_mesh(const std::string& path);

/// Writes BAMG's metric file: "N 3" then one symmetric tensor per vertex.
void write_bamg_metric(const std::vector<Eigen::Matrix2d>& metric, std::ostream& out);
void write_bamg_metric(const std::vector<Eigen::Matrix2d>& metric, const std::string& path);

}  // namespace quadapt
