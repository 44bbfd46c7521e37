#pragma once
// Gmsh MSH files <-> Mesh (docs/design.md §3).
//
// Reading: MSH 4.1 (ASCII and binary) and MSH 2.2 (ASCII and binary). 2D meshes of 3-node
// triangles and 4-node quads, or curved quads of geometric order 2 to 6 (9-, 16-, 25-, 36-,
// 49-node quadrangles, MSH types 10, 36, 37, 38, 47, Gmsh's node ordering; one order per mesh): their
// high-order nodes become Mesh::curved control points (mesh/curved.hpp) and Mesh::nodes keeps
// only the vertices. 2- to 7-node lines become boundary edges of their physical group (by
// name from $PhysicalNames, else "boundary_<tag>"); points and other element types of lower
// dimension are ignored, 2D elements of other types are an error. Nodes are renumbered 0..n-1,
// cells in file order. $ElementData views become CellFields, $ElementNodeData views become
// CellNodeFields (a view with an $InterpolationScheme of a tensor-product GLL basis of degree p
// written by us gets degree = p). The last time step of each view is kept.
// When the file has no boundary lines (PHiLiP's frame files), the boundary is the mesh's free
// edges, split at corners (mesh/boundary.hpp).
//
// Writing: MSH 4.1 ASCII with $PhysicalNames, $Entities (one curve per boundary group, one
// surface), $Nodes, $Elements (boundary lines, then cells), then one view per field. Curved
// meshes are written as 9- to 49-node quads with 3- to 7-node boundary lines; high-order
// nodes follow the vertices, shared between cells that hold the same point. Numbers are
// printed with 17 significant digits so reading back is bit-exact. Gmsh opens the result and
// shows every field (the DG field through $InterpolationScheme). Written atomically.
//
// Every error is an InputError "PATH: problem" (truncated file, unsupported version, missing
// section, NaN coordinate, unknown node, unsupported element type, field of wrong length...).
#include <iosfwd>
#include <string>

#include "core/atomic_file.hpp"
#include "mesh/mesh.hpp"
#include "mesh/validate.hpp"

namespace quadapt {

/// Reads a mesh with its fields ("-": standard input) and records `path` as an input of this
/// process (core/path_guard). Throws InputError naming `path` and the problem.
Mesh read_msh(const std::string& path);

/// read_msh, then validate_mesh(mesh, path, v): how a tool takes an input mesh.
Mesh read_valid_msh(const std::string& path, const ValidateOptions& v = {});

/// Writes MSH 4.1 ASCII through atomic_write ("-": standard output; see core/atomic_file), and
/// PATH.opt beside it when the mesh has a DG field and PATH is a regular file, so Gmsh displays
/// it smoothly (io/gmsh_options.hpp).
void write_msh(const Mesh& mesh, const std::string& path);
/// The same staged in `batch` (core/atomic_file.hpp) with its Gmsh options file: both are
/// replaced at batch.commit(), neither if anything added to the batch fails first.
void write_msh(const Mesh& mesh, const std::string& path, OutputBatch& batch);

/// Stream variants (path only used in messages).
Mesh read_msh(std::istream& in, const std::string& path_for_messages);
void write_msh(const Mesh& mesh, std::ostream& out);

}  // namespace quadapt
