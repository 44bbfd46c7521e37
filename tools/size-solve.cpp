// size-solve: the global size field and the target frame M = V^-1 (thesis §5.3-5.4, eqs.
// 5.17-5.25, 3.13; docs/design.md §3-4). See docs/size-solve.md.
#include <algorithm>
#include <cmath>
#include <string>

#include "cli/tool.hpp"
#include "core/format.hpp"
#include "io/msh.hpp"
#include "mesh/validate.hpp"
#include "sizing/size_frame.hpp"
#include "sizing/size_field.hpp"

int main(int argc, char** argv) {
  using namespace quadapt;
  Tool tool("size-solve", "Optimal size field and target frame (Vinv) for a complexity target",
            "Feature-based (default): the density d per cell minimising the L_q error model "
            "sum B d^(-q(p+1)/2) area under the continuous complexity sum d (p+1)^2 area = C "
            "(Problem 2): d = (q B / (2 lambda (p+1)))^(2/(q(p+1)+2)) (corrected eq. 5.21), lambda "
            "by bisection to a relative 1e-10, safeguards included. Goal-oriented (--dwr): target "
            "area alpha_k x current area with alpha_k from the log-space quadratic fit of the DWR "
            "indicator (eqs. 5.22-5.25), eta_ref by bisection so the complexity is C. Then h = "
            "1/(2 sqrt(d)), h1 = h sqrt(rho), h2 = h / sqrt(rho) (the target element spans "
            "+-v, +-w: edges 2h1 x 2h2) and M = V^-1 = diag(1/h1, 1/h2) R(-theta) (eq. 3.13), "
            "written as the 9-component cell field Vinv (row-major 3x3, zero-padded, M upper-left: "
            "PHiLiP's layout; note PHiLiP's own files use full-edge sizes, M_PHiLiP = M/2) plus h, "
            "theta, rho (and alpha). Safeguards: rho clamped to [1/A, A] with A = "
            "--max-anisotropy (B re-evaluated for the cap); every half-axis h, h1, h2 in [--hmin, --hmax] (defaults "
            "1e-6 sqrt(|domain|) and 0.125 sqrt(|domain|): the coarsest element spans a quarter "
            "of the domain's width); optional --gradation G: h_k <= G h_j between face neighbours. A target the "
            "bounds cannot reach is an error (exit 2, nothing written).");
  std::string in, out, dwr;
  double complexity = 0, growth = 0;
  SizeOptions opt;
  GoalOptions gopt;
  auto& app = tool.app();
  app.add_option("SHAPE", in, "SHAPE mesh from estimate-frame (fields theta, rho, B, A1, A2, p)")
      ->required()
      ->check(CLI::ExistingFile);
  app.add_option("-o,--output", out, "FRAME mesh (.msh); report beside it as .json")->required();
  auto* c = app.add_option("--complexity", complexity, "Target continuous complexity C (DOFs)");
  auto* g = app.add_option("--growth", growth, "Target C = G x current DOFs (cells x (p+1)^2)");
  c->excludes(g);
  app.add_option("--dwr", dwr, "Goal-oriented: per-cell DWR indicator 'dwr' on the SHAPE mesh (from adjoint)")
      ->check(CLI::ExistingFile);
  app.add_option("--norm-q", opt.q, "Exponent q of the L_q error norm (feature-based)")->capture_default_str();
  app.add_option("--max-anisotropy", opt.max_anisotropy,
                 "Maximum h1/h2 (PHiLiP's per-axis [0.2, 5] for L_p-CVT = 25; its BAMG [0.1, 10] = 100)")
      ->capture_default_str();
  app.add_option("--hmin", opt.hmin, "Minimum half-axis h2 (and h); 0 = 1e-6 sqrt(|domain|)")->capture_default_str();
  app.add_option("--hmax", opt.hmax, "Maximum half-axis h1 (and h); 0 = 0.125 sqrt(|domain|)")->capture_default_str();
  app.add_option("--gradation", opt.gradation, "Max ratio of h between face neighbours (> 1; 0 = off)")
      ->capture_default_str();
  app.add_option("--r-max", gopt.r_max, "Goal-oriented: maximum refinement factor r_max")->capture_default_str();
  app.add_option("--c-max", gopt.c_max, "Goal-oriented: maximum coarsening factor c_max")->capture_default_str();

  return tool.run(argc, argv, [&] {
    tool.input(in);
    if (!dwr.empty()) tool.input(dwr);
    tool.output_mesh(out);
    if (complexity <= 0 && growth <= 0) throw InputError("", "give --complexity C > 0 or --growth G > 0");
    Mesh shape, dwrmesh;
    {
      auto ph = tool.phase("read");
      shape = tool.read_mesh(in);
      if (!dwr.empty()) {
        dwrmesh = read_valid_msh(dwr);
      }
    }
    const ShapeData sd = read_shape(shape, in);
    const int n = sd.p + 1;
    const double dofs = static_cast<double>(shape.num_cells()) * n * n;
    opt.complexity = growth > 0 ? growth * dofs : complexity;
    tool.option("mode", dwr.empty() ? "feature" : "goal");
    if (growth > 0) tool.option("growth", growth);
    tool.option("q", opt.q);
    tool.option("max_anisotropy", opt.max_anisotropy);
    tool.option("hmin", opt.hmin);
    tool.option("hmax", opt.hmax);
    tool.option("gradation", opt.gradation);
    SizeResult r;
    {
      auto ph = tool.phase("solve");
      if (dwr.empty()) {
        r = solve_feature_size(shape, opt, in);
      } else {
        tool.option("r_max", gopt.r_max);
        tool.option("c_max", gopt.c_max);
        check_same_cells(shape, dwrmesh, dwr);
        const CellField* e = dwrmesh.cell_field("dwr");
        if (!e || e->ncomp != 1) throw InputError(dwr, "no scalar cell field \"dwr\" (expected the output of adjoint)");
        r = solve_goal_size(shape, e->values, opt, gopt, dwr);
      }
    }
    Mesh frame = make_frame_mesh(shape, r);
    auto& rep = tool.report();
    rep.update(to_json(r));
    rep["cells"] = shape.num_cells();
    rep["current_dofs"] = dofs;
    tool.log("target " + sci(r.target_complexity) + " DOFs, continuous complexity " +
             sci(r.continuous_complexity) + " (~" + std::to_string(std::lround(r.continuous_complexity / (n * n))) +
             " cells of p = " + std::to_string(r.p) + ")");
    {
      auto ph = tool.phase("write");
      write_msh(frame, out);
    }
  });
}
