// adjoint SOL.msh -c CASE.json -o DWR.msh: dual-weighted residual of the case's boundary
// functional on the degree-(p+1) space (thesis eqs. 2.25-2.27). See docs/adjoint.md.
#include <chrono>
#include <cmath>
#include <optional>
#include <sstream>
#include <string>

#include "adjoint/dwr.hpp"
#include "case/case.hpp"
#include "case/solved_case.hpp"
#include "cli/solver_options.hpp"
#include "cli/tool.hpp"
#include "dg/degree.hpp"
#include "core/format.hpp"
#include "dg/solve.hpp"
#include "io/msh.hpp"
#include "mesh/validate.hpp"

int main(int argc, char** argv) {
  using namespace quadapt;
  Tool tool("adjoint", "Dual-weighted residual (DWR) estimate of the functional error on the p+1 space",
            "Reads the degree-p DG solution 'u' of dgsolve (SOL), injects it into the degree-(p+1) space on "
            "the same mesh, evaluates the fine residual R_h(u_h^H) and the fine Jacobian A_h there, solves "
            "the fine adjoint A_h^T psi = (dJ/du)^T at the injected solution (J = integral of u^2 over the "
            "case's functional boundary; thesis eq. 2.25) and writes DWR = SOL's mesh and fields plus the "
            "per-cell DWR eta_k = |psi_k^T R_k| as the cell field 'dwr' (eq. 2.27) and the adjoint as the "
            "degree-(p+1) DG field 'psi'. The report DWR.json holds functional (J_H(u_H)), "
            "functional_exact, functional_error (|J(u) - J_H(u_H)|), functional_error_signed, "
            "functional_error_estimate (-psi^T R, the estimate of J(u) - J_H(u_H), eq. 2.26), sum_eta, "
            "effectivity (estimate / signed error), functional_corrected (J_H + estimate), the solver and "
            "the wall time of every phase. The case and the penalty factor are those SOL was solved with "
            "(dgsolve records them in SOL): another PDE is refused, the penalty taken from SOL unless given.");
  std::string in, out, case_path, field = "u", solver = "auto", ordering = "auto";
  AdjointOptions opt;
  bool no_fallback = false;
  auto& app = tool.app();
  app.add_option("SOL", in, "dgsolve output (.msh) with the DG field 'u'")->required()->check(CLI::ExistingFile);
  app.add_option("-c,--case", case_path, "Case file (.json) with a functional {\"boundary\": NAME}")
      ->required()
      ->check(CLI::ExistingFile);
  app.add_option("-o,--output", out, "Output mesh with the fields 'dwr' and 'psi' (.msh); report beside it as .json")
      ->required();
  app.add_option("--field", field, "Name of the DG solution field in SOL")->capture_default_str();
  app.add_option("--solver", solver,
                 "Adjoint linear solver: auto (pure advection: one exact block sweep downstream first; "
                 "else gmres-2level, then gmres-bilu0, then umfpack if they do not converge; "
                 "docs/adjoint.md), gmres-2level, gmres-bilu0, bicgstab-bilu0, gmres-bjacobi, bicgstab-ilut, "
                 "umfpack, sparselu")
      ->capture_default_str();
  app.add_option("--rtol", opt.solver.rtol, "Relative residual tolerance of iterative solvers")->capture_default_str();
  add_coarse_degree_option(app, opt.solver.coarse_degree, "the adjoint degree P+1");
  app.add_option("--max-iterations", opt.solver.max_iterations, "Iteration limit of iterative solvers")
      ->capture_default_str();
  app.add_flag("--no-fallback", no_fallback,
               "Fail instead of falling back to UMFPACK when the iterative solver does not converge");
  app.add_option("--ordering", ordering,
                 "Cell order of the adjoint solve (block sweep / block ILU(0)): auto (= flow), flow (downstream "
                 "first, as dgsolve orders them: pure advection a topological order of the reversed flow's "
                 "upwind graph, else the cells sorted along -c, or along y when c = 0; independent of the "
                 "file's cell order) or mesh (the file's order)")
      ->capture_default_str();
  CLI::Option* penalty_option =
      app.add_option("--penalty", opt.dg.penalty_factor,
                     "SIPG penalty factor, as given to dgsolve (the fine space takes factor p/(p+2) on interior faces, "
                     "the primal's sigma; keep it >= 5, docs/adjoint.md). Default: the factor SOL records "
                     "($SolvedCase), else 20");

  const auto as_typed = [](double v) {  // 0.5, not 5.000e-01
    std::ostringstream f;
    f << v;
    return f.str();
  };
  return tool.run(argc, argv, [&] {
    auto start = std::chrono::steady_clock::now();
    tool.input(in);
    tool.input(case_path);
    tool.output_mesh(out);
    opt.solver.kind = parse_linear_solver(solver);
    if (ordering == "auto")
      opt.ordering = AdjointOrdering::Auto;
    else if (ordering == "flow")
      opt.ordering = AdjointOrdering::Flow;
    else if (ordering == "mesh")
      opt.ordering = AdjointOrdering::Mesh;
    else
      throw InputError("", "--ordering '" + ordering + "': expected auto, flow or mesh");
    opt.fallback_direct = !no_fallback;
    tool.option("solver", linear_solver_name(opt.solver.kind));
    Mesh mesh;
    Case cs;
    Eigen::VectorXd U;
    int p = 0;
    {
      auto ph = tool.phase("read");
      ValidateOptions v = ValidateOptions::cells(CellKind::Quads);
      v.allow_curved = true;  // the DWR uses only the DG discretisation, which integrates on the curved map
      mesh = tool.read_mesh(in, v);
      U = read_solution_field(mesh, field, in, p);
      check_degree(p, in + ": the solution's degree p =", kMaxAdjointDegree);  // the fine space is p + 1
      cs = load_case(case_path);
      if (!cs.has_functional())
        throw InputError(case_path, "the case has no functional; add \"functional\": {\"boundary\": NAME}");
      check_case_boundaries(cs, mesh);
      if (!mesh.solved_case.empty())
        if (const auto diff = solved_case_differences(mesh.solved_case, cs, in); !diff.empty()) {
          std::string keys;
          for (const std::string& k : diff) keys += (keys.empty() ? "" : ", ") + k;
          throw InputError(case_path, "is not the PDE " + in + " was solved with (" + keys +
                                          " differ): the DWR needs the primal's case; give the case dgsolve "
                                          "solved with (adding a \"functional\" to it is fine)");
        }
      if (const auto solved = mesh.solved_case.empty() ? std::nullopt : solved_penalty(mesh.solved_case, in)) {
        if (penalty_option->count() == 0)
          opt.dg.penalty_factor = *solved;
        else if (opt.dg.penalty_factor != *solved)
          tool.warn("--penalty " + as_typed(opt.dg.penalty_factor) + " is not the factor " + in +
                   " was solved with (" + as_typed(*solved) +
                   "): the fine space's penalty is not the primal's; leave --penalty out to take SOL's");
      }
    }
    tool.option("penalty", opt.dg.penalty_factor);
    // a small factor makes the fine space's penalty too weak for its indicators (a reviewer's
    // --penalty 0.5 on a solution solved at 20: estimate 0.24 for a true error 9e-9, exit 0)
    if (opt.dg.penalty_factor < 5)
      tool.warn("--penalty " + as_typed(opt.dg.penalty_factor) +
               " is below 5: the indicators lose their meaning (docs/adjoint.md); give the factor dgsolve "
               "solved with (default 20)");
    // accepted (the thesis's S-shock and boundary layer with diffusion do it), but rarely meant
    if (cs.is_dirichlet(cs.functional_boundary))
      tool.warn("the functional boundary '" + cs.functional_boundary + "' has Dirichlet data in " + case_path +
               ": J = integral of u_h^2 there measures the weak boundary condition's mismatch, so a goal loop "
               "refines along that boundary rather than where the solution's error is; put the functional on a "
               "boundary without Dirichlet data (docs/adjoint.md, Limitations)");
    tool.log(std::to_string(mesh.num_cells()) + " cells, p = " + std::to_string(p) + " -> fine p = " +
             std::to_string(p + 1) + ", " + std::to_string(static_cast<long long>(mesh.num_cells()) * (p + 2) * (p + 2)) +
             " fine dofs");

    const DWRResult r = compute_dwr(mesh, cs, U, p, opt);
    auto& rep = tool.report();
    rep.update(to_json(r), true);  // merge_objects: the phase timings stay
    tool.log("adjoint solved with " + r.solve.solver + " (" + std::to_string(r.solve.iterations) +
             " iterations); estimate " + sci(r.estimate) + ", true error " +
             sci(r.functional_error));
    if (const std::string note = fallback_note(r.solve); !note.empty()) tool.warn(note);
    if (const std::string note = coarse_degree_note(opt.solver.coarse_degree, p + 1, r.solve); !note.empty())
      tool.warn(note);

    {
      auto ph = tool.phase("write");
      add_dwr_fields(mesh, r);
      write_msh(mesh, out);
    }
    rep["case"] = case_path;
    if (!cs.name.empty()) rep["case_name"] = cs.name;
    rep["functional_boundary"] = cs.functional_boundary;
    rep["cells"] = mesh.num_cells();
    rep["time_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  });
}
