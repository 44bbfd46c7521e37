// refine: the baselines of the adaptive studies (thesis §2.5) — uniform and fixed-fraction
// refinement of an all-quad mesh, hanging nodes kept, 2:1 balanced. See docs/refine.md.
#include <string>

#include "cli/tool.hpp"
#include "gmsh/geometry.hpp"
#include "io/msh.hpp"
#include "mesh/snap.hpp"
#include "mesh/validate.hpp"
#include "refine/refine.hpp"

int main(int argc, char** argv) {
  using namespace quadapt;
  Tool tool("refine", "Uniform or fixed-fraction refinement of a quad mesh, with hanging nodes",
            "Splits quads isotropically into 4 (edge midpoints + centre). --uniform splits every "
            "cell. --by FIELD splits the share F (--fraction, default 0.3) of cells with the "
            "largest values of FIELD, a per-cell scalar ($ElementData with 1 component): 'A1' or "
            "'B' from estimate-frame for feature-based adaptation, 'dwr' from adjoint for "
            "goal-oriented adaptation. Per-node fields (such as the solution 'u') and "
            "multi-component fields (such as 'Vinv') cannot be indicators. Then more cells are "
            "split until face neighbours differ by at most one level (2:1, thesis Fig. 2.2); the "
            "levels are read off the geometry, so the input may be conforming or a previous "
            "2:1 output. Existing hanging nodes are reused as midpoints. Boundary edges of split "
            "cells become two edges of the same group. The output carries no fields (they "
            "belong to the old mesh) unless --keep-fields copies the scalar cell fields to the "
            "children. Report: cells before/after, flagged, added by balancing, hanging nodes.");
  std::string in, out, geometry;
  bool uniform = false;
  RefineOptions opt;
  opt.fraction = 0.3;
  auto& app = tool.app();
  app.add_option("MESH", in, "Input all-quad mesh (.msh), conforming or 2:1 non-conforming")
      ->required()
      ->check(CLI::ExistingFile);
  app.add_option("-o,--output", out, "Output mesh (.msh); report beside it as .json")->required();
  auto* u = app.add_flag("--uniform", uniform, "Split every cell into 4");
  auto* by = app.add_option("--by", opt.by,
                            "Indicator: name of a 1-component cell field of MESH (A1, B, dwr, ...)");
  auto* fr = app.add_option("--fraction", opt.fraction,
                            "Share F in (0, 1] of cells flagged by --by (ceil(F N) cells)")
                 ->capture_default_str();
  app.add_flag("--keep-fields", opt.keep_scalar_fields,
               "Copy every 1-component cell field of MESH to the children (piecewise constant)");
  app.add_option("--geometry", geometry, "Snap the boundary nodes (the new mid-edge ones) to the true curves of this "
                 "geometry (.geo, .brep, .step; named physical curves = MESH's boundary names; docs/curved.md)")
      ->check(CLI::ExistingFile);
  u->excludes(by);
  u->excludes(fr);
  fr->needs(by);

  return tool.run(argc, argv, [&] {
    tool.input(in);
    if (!geometry.empty()) tool.input(geometry);
    tool.output_mesh(out);
    std::unique_ptr<BoundaryGeometry> g;
    if (!geometry.empty()) {
      auto ph = tool.phase("geometry");
      g = open_geometry(geometry);
      tool.option("geometry", geometry);
    }
    if (!uniform && opt.by.empty())
      throw InputError("", "choose --uniform or --by FIELD [--fraction F]");
    opt.mode = uniform ? RefineOptions::Mode::Uniform : RefineOptions::Mode::Fraction;
    tool.option("mode", uniform ? "uniform" : "fraction");
    if (!uniform) {
      tool.option("fraction", opt.fraction);
      tool.option("by", opt.by);
    }
    tool.option("keep_fields", opt.keep_scalar_fields);

    Mesh m;
    {
      auto ph = tool.phase("read");
      m = tool.read_mesh(in, ValidateOptions::cells(CellKind::Quads));
    }
    RefineStats s;
    Mesh r;
    {
      auto ph = tool.phase("refine");
      r = refine_mesh(m, opt, &s, in);
    }
    if (g) {
      auto ph = tool.phase("snap");
      const SnapStats ss = snap_to_geometry(r, *g, in, s.hanging_after == 0);
      tool.report()["snap"] = {{"boundary_nodes", ss.boundary_nodes}, {"moved", ss.moved}, {"max_move", ss.max_move},
                               {"max_distance", ss.max_distance}, {"max_interior_move", ss.max_interior_move}};
      for (const std::string& w : ss.warnings) tool.warn(in + ": " + w);
    }
    auto& rep = tool.report();
    rep["cells_before"] = s.cells_before;
    rep["cells"] = s.cells_after;
    rep["nodes_before"] = s.nodes_before;
    rep["nodes"] = s.nodes_after;
    rep["flagged"] = s.flagged;
    rep["added_by_balance"] = s.added_by_balance;
    rep["split"] = s.split;
    rep["hanging_nodes_before"] = s.hanging_before;
    rep["hanging_nodes"] = s.hanging_after;
    tool.log(std::to_string(s.cells_before) + " -> " + std::to_string(s.cells_after) + " cells (" +
             std::to_string(s.flagged) + " flagged, " + std::to_string(s.added_by_balance) +
             " added by 2:1 balancing), " + std::to_string(s.hanging_after) + " hanging nodes");
    {
      auto ph = tool.phase("write");
      write_msh(r, out);
    }
  });
}
