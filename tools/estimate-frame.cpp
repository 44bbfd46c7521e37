// estimate-frame: per-cell optimal frame shape and error constant from a DG solution
// (thesis §5.2, eqs. 5.8-5.16; docs/design.md §4). See docs/estimate-frame.md.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>

#include "case/expression.hpp"
#include "cli/tool.hpp"
#include "dg/degree.hpp"
#include "core/format.hpp"
#include "estimate/interpolate.hpp"
#include "estimate/estimate_frame.hpp"
#include "io/msh.hpp"
#include "mesh/validate.hpp"

int main(int argc, char** argv) {
  using namespace quadapt;
  Tool tool("estimate-frame", "Optimal frame shape (theta, rho) and error constant B per cell from a DG solution",
            "For each cell k: the degree-(p+1) polynomial reconstructed from the DG field u over k and "
            "its face neighbours by H1 projection (thesis eq. 5.8; hanging-node neighbours included; "
            "--patch vertex adds every cell sharing a vertex); its top-degree term P(y) (the Taylor "
            "term D^(p+1)u[y,...,y]/(p+1)!) gives the frame: long axis theta in [0, pi), anisotropy "
            "rho = h1/h2 >= 1 and the error constant B of the L_q model e = B d^(-q(p+1)/2) (eqs. "
            "5.15-5.16). --model polynomial (the default) keeps the thesis's orientation (below) and takes "
            "rho and B from the L_q integral of |P| itself over the element's ellipse, minimised over "
            "rho: every term of P counts, so a harmonic solution gets square elements. --model thesis uses the thesis's bound: the largest directional "
            "derivative A1 with direction phi and the perpendicular one A2 (eqs. 5.10-5.13), theta = "
            "phi - pi/2 and rho = (A1/A2)^(1/(p+1)), i.e. elements THIN along the largest derivative; "
            "it asks for rho = its cap wherever A2 vanishes (for p = 2, everywhere on a harmonic "
            "solution). Observed-error floor (--observed-floor TAU, default 4): where the misfit of the "
            "reconstruction to u, ||u~ - u||^q over the cell, exceeds TAU times its typical (median) "
            "ratio to the model's error at the cell's size, B is raised by the excess: a smooth Taylor "
            "model under-predicts singular and unresolved cells. rho is capped at --max-anisotropy; cells "
            "whose (p+1)-th term is rounding noise "
            "get A1 = A2 = B = 0, phi = theta = 0, rho = 1. SOL may have curved cells (geometric order 2..6): "
            "the field lives and is reconstructed on their curved map. Output: SOL's geometry (the "
            "vertex view of curved cells) and boundary groups with cell fields theta, rho, B, A1, A2, "
            "phi, model_A1, model_A2 (the thesis bound's coefficients that give the model's rho and B: "
            "A1 and A2 with --model thesis; A1 A2 = (I/2pi)^(2/q), A1/A2 = rho^(p+1) with polynomial; "
            "size-solve re-evaluates B from them at its --max-anisotropy) and p (the DG degree); the "
            "solution itself is not copied. Input for size-solve. With --exact EXPR "
            "-p P the field is instead the degree-P GLL interpolant of the expression EXPR(x, y) on the "
            "quad mesh SOL (adaptation to a known function, no solver). See docs/estimate-frame.md.");
  std::string in, out, patch = "face", model = "polynomial", exact;
  int p_exact = 0;
  EstimateOptions opt;
  auto& app = tool.app();
  app.add_option("SOL", in, "DG solution (.msh from dgsolve, with the DG field 'u')")
      ->required()
      ->check(CLI::ExistingFile);
  app.add_option("-o,--output", out, "SHAPE mesh (.msh); report beside it as .json")->required();
  app.add_option("--field", opt.field, "Name of the DG field")->capture_default_str();
  app.add_option("--norm-q", opt.q, "Exponent q of the L_q error norm (>= 1)")->capture_default_str();
  app.add_option("--patch", patch, "Reconstruction patch: face (thesis Fig. 5.1) or vertex (3x3-like)")
      ->check(CLI::IsMember({"face", "vertex"}))
      ->capture_default_str();
  app.add_option("--model", model,
                 "Error model: polynomial (the L_q integral of the whole (p+1)-th term over the element) or "
                 "thesis (eqs. 5.9-5.16: A1 and the perpendicular A2 only)")
      ->check(CLI::IsMember({"polynomial", "thesis"}))
      ->capture_default_str();
  app.add_option("--observed-floor", opt.observed_floor,
                 "Raise B where the reconstruction's misfit exceeds TAU x its median ratio to the model "
                 "(0 = off, else >= 1; with --model thesis, 0 gives the thesis's eqs. 5.9-5.16 exactly)")
      ->check(CLI::Validator(
          [](std::string& s) {
            char* end = nullptr;
            const double v = std::strtod(s.c_str(), &end);
            if (end == s.c_str() || *end != '\0') return std::string("not a number: ") + s;
            return v == 0 || v >= 1 ? std::string() : std::string("must be 0 (off) or >= 1, got ") + s;
          },
          "{0} U [1, inf)", "0 or >= 1"))
      ->capture_default_str();
  auto* ex = app.add_option("--exact", exact, "Use the GLL interpolant of this expression in x, y instead of the field");
  auto* pe = app.add_option("-p,--degree", p_exact, "DG degree P of the --exact interpolant (" + degree_range_text() + ")");
  ex->needs(pe);
  pe->needs(ex);
  app.add_option("--max-anisotropy", opt.max_anisotropy,
                 "Numerical cap on rho = h1/h2 (the user limit is size-solve's --max-anisotropy)")
      ->capture_default_str();

  return tool.run(argc, argv, [&] {
    tool.input(in);
    tool.output_mesh(out);
    opt.patch = patch == "vertex" ? PatchKind::Vertex : PatchKind::Face;
    tool.option("field", opt.field);
    tool.option("q", opt.q);
    tool.option("patch", patch);
    opt.model = model == "thesis" ? ErrorModel::Thesis : ErrorModel::Polynomial;
    tool.option("model", model);
    tool.option("observed_floor", opt.observed_floor);
    tool.option("max_anisotropy", opt.max_anisotropy);
    // parsed before reading: a mistake in it is the option's, named as such ("--exact 'x*':
    // column 3: ..."; it said only "column 3: expression ends unexpectedly")
    Expr e;
    if (!exact.empty()) {
      check_degree(p_exact, "-p");
      try {
        e = parse_expression(exact);
      } catch (const InputError& err) {
        throw InputError("--exact '" + exact + "'", err.what());
      }
    }
    Mesh sol;
    {
      auto ph = tool.phase("read");
      ValidateOptions vo = ValidateOptions::cells(CellKind::Quads);
      vo.allow_curved = true;  // reconstructed on the curved map (docs/curved.md)
      sol = tool.read_mesh(in, vo);
      if (!exact.empty()) {
        sol.set_field(interpolate_dg(sol, p_exact, [&](double x, double y) {
          const double v = evaluate(e, x, y);
          if (!std::isfinite(v))
            throw InputError("--exact '" + exact + "' is not finite at " + sci_point(x, y) + " on " + in);
          return v;
        }, opt.field));
        tool.option("exact", exact);
        tool.option("degree", p_exact);
      }
    }
    EstimateResult r;
    {
      auto ph = tool.phase("estimate");
      r = estimate_frame(sol, opt, in);
    }
    Mesh shape = make_shape_mesh(sol, r);
    auto& rep = tool.report();
    const int nc = sol.num_cells();
    const int n = r.p + 1;
    rep["cells"] = nc;
    rep["geometric_order"] = sol.geometric_order();
    rep["p"] = r.p;
    rep["dofs"] = static_cast<long long>(nc) * n * n;
    double a1max = 0, bsum = 0;
    int flat = 0;
    std::vector<double> rho;
    for (int k = 0; k < nc; ++k) {
      a1max = std::max(a1max, r.A1[k]);
      if (r.A1[k] == 0) ++flat;
      rho.push_back(r.rho[k]);
      // the model's L_q error^q at the current cell sizes (d = 1/area, optimal shape assumed)
      const double area = std::abs(cell_area(sol, k));
      bsum += r.B[k] * std::pow(area, (opt.q * n + 2) / 2);
    }
    std::sort(rho.begin(), rho.end());
    rep["A1_max"] = a1max;
    rep["cells_without_derivative"] = flat;
    rep["rho_min"] = rho.front();
    rep["rho_median"] = rho[rho.size() / 2];
    rep["rho_max"] = rho.back();
    rep["model_error_at_current_sizes"] = std::pow(bsum, 1 / opt.q);
    rep["misfit_ratio_median"] = r.misfit_ratio_median;
    rep["cells_raised_by_misfit"] = r.cells_raised;
    tool.log(std::to_string(nc) + " cells, p = " + std::to_string(r.p) + ", median anisotropy " +
             sci(rho[rho.size() / 2]) + ", " + std::to_string(flat) + " cells without (p+1)-th derivative, " +
             std::to_string(r.cells_raised) + " raised by the observed-error floor");
    {
      auto ph = tool.phase("write");
      write_msh(shape, out);
    }
  });
}
