#pragma once
// The true boundary of a domain from a CAD file the Gmsh SDK opens (.geo, .brep, .step, ...):
// its named physical curves as a BoundaryGeometry (mesh/geometry.hpp). Behind the SDK adapter;
// the model stays loaded (in Gmsh model "quadapt-geometry", made current for each query) while
// the returned object lives. Not thread-safe (Gmsh's global state).
#include <memory>
#include <string>

#include "mesh/geometry.hpp"

namespace quadapt {

/// Opens `path` and keeps every curve of a physical group with a name; the names become the
/// boundary-group names of meshes made on the geometry. Throws InputError("path: ...") when Gmsh
/// cannot open the file, when it has no physical curves or a physical curve without a name, when
/// a curve belongs to two physical groups, or when the geometry is not planar (z != 0).
std::unique_ptr<BoundaryGeometry> open_geometry(const std::string& path);

}  // namespace quadapt
