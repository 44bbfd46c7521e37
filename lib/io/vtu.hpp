#pragma once
// Mesh -> VTK XML UnstructuredGrid (.vtu), for ParaView (docs/file-formats.md §6).
//
// Every field goes into the file:
//  - CellFields (theta, rho, B, A1, A2, h, alpha, dwr, ... and the 9-component frame Vinv) are
//    CellData with their component count; ParaView treats a 9-component array as a 3x3 tensor
//    (row-major, as in the .msh file).
//  - A DG CellNodeField of degree p (the solution u) makes every quad a
//    VTK_LAGRANGE_QUADRILATERAL (type 70) of degree q = the largest DG degree in the mesh, with
//    its own (q+1)^2 points (DG fields are discontinuous between cells) at the equispaced
//    reference points xi_a = -1 + 2a/q, mapped by the cell's bilinear map, and the field's values
//    there as PointData. VTK interpolates a Lagrange quad on equispaced reference nodes, so it
//    reproduces the degree-p polynomial exactly (p <= q) and the straight-sided geometry too.
//    Point order is VTK's (vtkHigherOrderQuadrilateral::PointIndexFromIJK): corners
//    (0,0) (q,0) (q,q) (0,q); then the edges bottom (a = 1..q-1, b = 0), right (a = q, b = 1..q-1),
//    top (a = 1..q-1, b = q), left (a = 0, b = 1..q-1), each in increasing parametric order;
//    then the interior, a fastest. (a, b) index (xi, eta) on the reference square [-1,1]^2,
//    whose corners are the cell's vertices v0..v3 as in Gmsh.
//  - A CellNodeField of vertex values (degree -1) is written as PointData too, interpolated
//    bilinearly when the cells are Lagrange quads.
//  - Without CellNodeFields the cells are linear (VTK_QUAD 9, VTK_TRIANGLE 5) on the shared
//    mesh nodes. With them, every cell has its own points (VTK_QUAD / VTK_TRIANGLE when q = 1).
// Also written: CellData "cell" (1-based cell number = the element tag in quadapt's .msh files).
// ASCII, numbers with 17 significant digits (values read back bit-exactly). Written atomically.
// Throws InputError for a DG field on a mesh with triangles (quadapt's DG is on quads only).
#include <iosfwd>
#include <string>

#include "mesh/mesh.hpp"

namespace quadapt {

/// VTK cell type codes used (vtkCellType.h).
constexpr int kVtkTriangle = 5;
constexpr int kVtkQuad = 9;
constexpr int kVtkLagrangeQuadrilateral = 70;

/// Reference index (a, b), 0 <= a, b <= q, of point k of a degree-q VTK Lagrange quadrilateral
/// (the order above). Returned as a + (q+1) b.
int vtk_lagrange_quad_node(int q, int k);

/// Writes the mesh and its fields as VTK XML UnstructuredGrid ASCII, atomically.
void write_vtu(const Mesh& mesh, const std::string& path);
/// Stream variant (`path_for_messages` names the file in errors).
void write_vtu(const Mesh& mesh, std::ostream& out, const std::string& path_for_messages = "");

enum class MeshFileFormat { Msh, Vtu };
/// The format a mesh output's name asks for: ".vtu" VTK XML; ".msh", no extension, "-" or a
/// device MSH 4.1. Any other extension (".vtk" would otherwise get MSH text) throws InputError
/// naming the path — call it before any work, as picture_format for pictures.
MeshFileFormat mesh_file_format(const std::string& path);

/// Writes `path` in mesh_file_format(path): VTK XML (write_vtu) or MSH 4.1 (write_msh).
void write_mesh_file(const Mesh& mesh, const std::string& path);

}  // namespace quadapt
