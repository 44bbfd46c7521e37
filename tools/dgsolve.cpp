// dgsolve MESH.msh -c CASE.json -p P -o SOL.msh: high-order DG solution of the case's
// advection-diffusion problem (thesis eq. 2.9, eq. 6.2). See docs/dgsolve.md.
#include <chrono>
#include <string>

#include "case/boundary_conditions.hpp"
#include "case/case.hpp"
#include "case/solved_case.hpp"
#include "cli/solver_options.hpp"
#include "cli/tool.hpp"
#include "dg/degree.hpp"
#include "core/format.hpp"
#include "dg/solve.hpp"
#include "io/msh.hpp"
#include "mesh/curved.hpp"
#include "mesh/validate.hpp"

int main(int argc, char** argv) {
  using namespace quadapt;
  Tool tool("dgsolve", "High-order DG solution of steady advection-diffusion on an all-quad mesh",
            "Solves div(D grad u) - c . grad u = S (thesis eq. 6.2) on MESH (straight-sided quads, conforming "
            "or with 2:1 hanging nodes, or curved quads of geometric order 2..6 (2:1 only where the coarse edge and its halves trace the same curve): Gmsh's 9- to "
            "49-node quadrangles, integrated on their curved map) with the discontinuous Galerkin method of thesis eq. 2.9: tensor "
            "Lagrange basis of degree P on Gauss-Lobatto points, upwind advective flux, symmetric interior "
            "penalty (factor 20 p(p+1)/h, n^T D n) for the full diffusion tensor, weak Dirichlet data (CASE's "
            "expressions, else the exact solution) on the boundaries CASE names (others: Neumann data, CASE's or "
            "the exact solution's diffusive flux, upwind advection). CASE (JSON, docs/cases.md) gives D, c, the exact solution u(x, y) as an "
            "expression (the source S is its exact symbolic derivative), the Dirichlet boundaries and the "
            "functional J = int over a boundary of u^2. Output: SOL = MESH with the DG field 'u' (the "
            "(p+1)^2 GLL nodal values per cell; Gmsh shows it as a high-order field) and the report "
            "SOL.json: cells, p, dofs, boundaries (per group: condition, data from the case or the exact solution, "
            "added from free edges), l2_error, functional, functional_exact, functional_error, solver, "
            "timings per phase, peak memory.");
  std::string in, out, case_path, solver = "auto";
  DGSolveOptions opt;
  auto& app = tool.app();
  app.add_option("MESH", in, "Input all-quad mesh (.msh), conforming or 2:1 non-conforming")
      ->required()
      ->check(CLI::ExistingFile);
  app.add_option("-c,--case", case_path, "Case file (.json): D, c, exact solution, boundaries, functional")
      ->required()
      ->check(CLI::ExistingFile);
  app.add_option("-p,--degree", opt.p, "Polynomial degree P (" + degree_range_text() + ")")->required();
  app.add_option("-o,--output", out, "Output mesh with the field 'u' (.msh); report beside it as .json")
      ->required();
  app.add_option("--solver", solver,
                 "Linear solver: auto (with diffusion gmres-2level then gmres-bilu0, without it gmres-bilu0 in "
                 "downwind order; then umfpack; a method whose rate misses 300 iterations is left early; "
                 "docs/dgsolve.md), gmres-2level, umfpack, sparselu, gmres-bilu0, bicgstab-bilu0, "
                 "gmres-bjacobi, bicgstab-ilut")
      ->capture_default_str();
  app.add_option("--rtol", opt.solver.rtol, "Relative residual tolerance of iterative solvers")
      ->capture_default_str();
  add_coarse_degree_option(app, opt.solver.coarse_degree, "P");
  app.add_option("--penalty", opt.dg.penalty_factor, "SIPG penalty factor (sigma = factor p(p+1) n^T D n / h)")
      ->capture_default_str();

  return tool.run(argc, argv, [&] {
    auto start = std::chrono::steady_clock::now();
    tool.input(in);
    tool.input(case_path);
    tool.output_mesh(out);
    opt.solver.kind = parse_linear_solver(solver);
    check_degree(opt.p, "degree -p");

    Mesh mesh;
    Case cs;
    {
      auto ph = tool.phase("read");
      ValidateOptions v = ValidateOptions::cells(CellKind::Quads);
      v.allow_curved = true;
      mesh = tool.read_mesh(in, v);
      cs = load_case(case_path);
      check_case_boundaries(cs, mesh);
    }
    const std::vector<GroupCondition> conditions = group_conditions(cs, mesh);
    tool.log("boundaries: " + conditions_text(conditions));
    if (const std::string w = free_edge_warning(cs, mesh, conditions, in); !w.empty()) tool.warn(w);
    if (mesh.cell_field("Vinv"))  // a frame file given as the mesh: legal, but rarely meant
      tool.log("note: " + in + " carries a frame (Vinv): solving on its cells, the mesh the frame was made on "
               "(the mesh the frame asks for is lpcvt's or bamgquad's output)");
    tool.log(std::to_string(mesh.num_cells()) + " cells, p = " + std::to_string(opt.p) + ", " +
             std::to_string(mesh.num_cells() * (opt.p + 1) * (opt.p + 1)) + " dofs");

    DGSolveResult r = dg_solve(mesh, cs, opt);
    auto& rep = tool.report();
    rep["timings"]["assemble"] = r.t_assemble;
    rep["timings"]["solve"] = r.t_solve;
    rep["timings"]["postprocess"] = r.t_postprocess;
    tool.log("solved with " + r.solve.solver + " in " + sci(r.t_solve) + " s; L2 error " +
             sci(r.l2_error));
    if (const std::string note = fallback_note(r.solve); !note.empty()) tool.warn(note);
    if (const std::string note = coarse_degree_note(opt.solver.coarse_degree, opt.p, r.solve); !note.empty())
      tool.warn(note);

    {
      auto ph = tool.phase("write");
      mesh.clear_fields();
      mesh.set_field(make_dg_field(r.U, r.p, mesh.num_cells(), "u"));
      mesh.solved_case = solved_case_record(cs, opt.dg.penalty_factor);  // adjoint: the same PDE and penalty
      write_msh(mesh, out);
    }
    rep["case"] = case_path;
    rep["boundaries"] = nlohmann::json::array();
    for (const GroupCondition& g : conditions)
      rep["boundaries"].push_back({{"name", g.name},
                                   {"tag", g.tag},
                                   {"edges", g.edges},
                                   {"condition", g.dirichlet ? "dirichlet" : "natural"},
                                   {"data", g.case_data ? "case" : "exact"},
                                   {"functional", g.functional},
                                   {"added_from_free_edges", g.from_free_edges}});
    if (!cs.name.empty()) rep["case_name"] = cs.name;
    rep["cells"] = r.cells;
    rep["p"] = r.p;
    rep["dofs"] = r.dofs;
    rep["hanging_faces"] = r.hanging_faces;
    rep["geometric_order"] = mesh.geometric_order();
    if (mesh.is_curved()) rep["curved_scaled_jacobian_min"] = min_scaled_jacobian(mesh).min;
    rep["l2_error"] = r.l2_error;
    if (r.has_functional) {
      rep["functional_boundary"] = cs.functional_boundary;
      rep["functional"] = r.functional;
      rep["functional_exact"] = r.functional_exact;
      rep["functional_error"] = r.functional_error;
    } else {
      rep["functional"] = nullptr;
      rep["functional_exact"] = nullptr;
      rep["functional_error"] = nullptr;
    }
    rep["solver"] = r.solve.solver;
    rep["solver_iterations"] = r.solve.iterations;
    rep["solver_relative_residual"] = r.solve.relative_residual;
    rep["solver_coarse_degree"] = r.solve.coarse_degree;
    rep["time_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  });
}
