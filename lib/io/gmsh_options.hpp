#pragma once
// FILE.msh.opt: the Gmsh options file written beside a mesh that carries a DG field, so that
// Gmsh shows the high-order solution smoothly on open. Gmsh merges "FILE.opt" automatically when
// it opens FILE (General.* / View[i].* statements in its .geo syntax).
//
// For every DG CellNodeField (degree p >= 1; i = its position among the file's n views as
// write_msh orders them: the CellFields first, then the CellNodeFields), with
// V = View[PostProcessing.NbViews - (n - i)] — the file's views are the last n Gmsh holds when
// it merges FILE.opt, also when other files were opened before (`gmsh a.msh b.msh`; View[i]
// would set a.msh's views from b.msh's options):
//   V.AdaptVisualizationGrid = 1;   evaluate the interpolation scheme on a refined grid
//   V.MaxRecursionLevel = L;        each cell drawn as 4^L sub-quads, 2^L >= 2p, capped
//                                   so that cells * 4^L <= 4e6 (L >= 1)
//   V.TargetError = -1;             refine uniformly to level L (no early stop)
// Other views keep Gmsh's defaults (all visible; pick one in Gmsh's view list).
#include <string>

#include "core/atomic_file.hpp"
#include "mesh/mesh.hpp"

namespace quadapt {

/// The options text for `mesh` written as a .msh file; empty when it has no DG field.
std::string gmsh_view_options(const Mesh& mesh);

/// Stages `msh_path`.opt in `batch` (write_msh's: the mesh and its options file are replaced
/// together, core/atomic_file.hpp) when gmsh_view_options is not empty. When it is empty, a stale
/// `msh_path`.opt that quadapt wrote earlier is removed after the commit (one of another origin is
/// kept). Nothing is done for outputs that are not files in a directory ("-", /dev/..., FIFOs).
void stage_gmsh_options(const Mesh& mesh, const std::string& msh_path, OutputBatch& batch);

}  // namespace quadapt
