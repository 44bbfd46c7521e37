// One adaptation step of the thesis's method through the quadapt library, without the tools:
// DG solve -> error model and frame -> L_p-CVT points -> all-quad mesh -> smoothed to the frame.
// Each step is the library call the tool of the same name makes, with the tool's defaults, so
// OUT.msh is byte for byte the loop's adapted.msh for the same frame (example.cpp_adapt_step
// checks it against dgsolve | estimate-frame | size-solve | lpcvt | recombine | quadsmooth).
//
//   adapt_step [MESH.msh [CASE.json [OUT.msh]]]   (defaults: examples/meshes/square16.msh,
//                                                 examples/cases/sshock.json, adapted.msh)
#include <cmath>
#include <cstdio>
#include <string>

#include "case/case.hpp"
#include "core/error.hpp"
#include "dg/solve.hpp"
#include "estimate/estimate_frame.hpp"
#include "frame/frame.hpp"
#include "io/msh.hpp"
#include "lpcvt/run.hpp"
#include "quad/frame_smooth.hpp"
#include "quad/recombine.hpp"
#include "sizing/size_field.hpp"
#include "sizing/size_frame.hpp"

int main(int argc, char** argv) {
  using namespace quadapt;
  const std::string dir = QUADAPT_EXAMPLES_DIR;
  const std::string mesh_path = argc > 1 ? argv[1] : dir + "/meshes/square16.msh";
  const std::string case_path = argc > 2 ? argv[2] : dir + "/cases/sshock.json";
  const std::string out = argc > 3 ? argv[3] : "adapted.msh";
  try {
    // 1. Solve: the DG solution u of degree p on the current mesh.
    Mesh mesh = read_valid_msh(mesh_path, ValidateOptions::cells(CellKind::Quads));
    const Case cs = load_case(case_path);
    DGSolveOptions solve;
    solve.p = 2;
    const DGSolveResult sol = dg_solve(mesh, cs, solve);
    mesh.set_field(make_dg_field(sol.U, sol.p, mesh.num_cells()));

    // 2. Frame: the error model per cell, the optimal sizes for 1.5x the DOFs, the frame field
    //    (in the canonical order read_frame gives it: the tools' results to the byte).
    const Mesh shape = make_shape_mesh(mesh, estimate_frame(mesh));
    SizeOptions size;
    size.complexity = 1.5 * sol.dofs;
    const SizeResult sizes = solve_feature_size(shape, size);
    const Frame frame = canonical_frame(frame_from_mesh(make_frame_mesh(shape, sizes), "frame"));

    // 3. Triangles: L_p-CVT points with the lpcvt tool's defaults (LpcvtJob::for_frame(); a
    //    default-built LpcvtJob is the bare method: no smoothing, gradation or orientation).
    lpcvt::LpcvtJob job = lpcvt::LpcvtJob::for_frame();
    nlohmann::json report;
    const lpcvt::Background bg = lpcvt::frame_background(frame, job, report);
    const lpcvt::LpcvtResult tri = lpcvt::mesh_background(bg, job, report);

    // 4. Quads: the metric matching in the frame lpcvt meshed (attached to its triangles as Vinv)
    //    and the split (recombine's default with a frame), then the corner fit to the frame's
    //    squares (quadsmooth --frame).
    RecombineOptions ro;
    ro.with_frame(frame_from_mesh(tri.mesh, "lpcvt").oriented());
    Mesh quads = recombine_to_all_quads(tri.mesh, ro);
    shape_smooth_to_frame(quads, frame);
    quads.clear_fields();
    write_msh(quads, out);

    std::printf("%d cells, p = %d, L2 error %.3e -> frame asks %.0f cells -> %d triangles -> %d quads (%s)\n",
                sol.cells, sol.p, sol.l2_error, frame.target_cells(), tri.mesh.num_cells(), quads.num_cells(),
                out.c_str());
    const bool ok = quads.all_quads() && std::abs(quads.num_cells() / frame.target_cells() - 1) < 0.25;
    return ok ? 0 : 1;
  } catch (const Error& e) {
    std::fprintf(stderr, "adapt_step: %s\n", e.what());
    return 2;
  }
}
