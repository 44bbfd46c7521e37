// lpcvt: points by L_p-CVT energy minimisation conforming to a frame field, then a constrained
// Delaunay triangulation (thesis ch. 4, Algorithms 1-3). See docs/lpcvt.md.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include "cli/parse_errors.hpp"
#include "cli/tool.hpp"
#include "core/format.hpp"
#include "core/atomic_file.hpp"
#include "io/msh.hpp"
#include "lpcvt/energy.hpp"
#include "lpcvt/lpcvt.hpp"
#include "lpcvt/metric_filter.hpp"
#include "lpcvt/quality.hpp"
#include "lpcvt/triangulate.hpp"
#include "mesh/validate.hpp"

int main(int argc, char** argv) {
  using namespace quadapt;
  using namespace quadapt::lpcvt;
  Tool tool(
      "lpcvt", "Triangles whose points minimise the L_p-CVT energy of a frame field",
      "Reads the background mesh FRAME.msh with its per-cell frame 'Vinv' (M = V^-1, 9 "
      "components, M in the upper-left 2x2), meshes the boundary curves by equidistribution in "
      "the metric (thesis eqs. 4.2-4.7; names kept), seeds interior points, then repeats "
      "{ L-BFGS (Moré-Thuente line search) on the L_p-CVT energy over the clipped Voronoi "
      "diagram (eq. 4.1, analytic gradient eqs. 4.8-4.11); split long / merge short Delaunay "
      "edges by the L_p line integral (eq. 4.12) } until fewer than 2% of the edges change in "
      "two consecutive cycles, and writes the constrained Delaunay triangulation with the "
      "boundary groups. Sizes: the metric is M_eff = scale * M with scale 1/4, so points are "
      "4h1 x 4h2 apart and the all-quad mesh made by 'recombine' (Blossom + split into 4) has "
      "edges 2h1 x 2h2, the frame's parallelogram (PHiLiP's files use full-edge sizes: "
      "--convention philip). --analytic saddle runs the thesis's "
      "validation (eq. 6.1 on [-1.3,1.3]^2, 20 random start points; --sampled: the metric "
      "sampled on a 16x16 grid) without FRAME. The report has points, requested_points, "
      "iterations, energy, grad_norm, converged and the whole convergence history. An "
      "optimiser that stops early still writes a valid mesh (\"converged\": false; with --strict "
      "exit code 1).");
  std::string in, out, analytic, voronoi_out, init = "", convention = "quadapt", cells_kind;
  double cell_alpha = 0.9;
  LpcvtOptions opt;
  double scale = -1;
  int grid = 16;
  bool sampled = false, strict = false;
  auto& app = tool.app();
  app.add_option("FRAME", in, "Background mesh with the cell field Vinv (.msh)")->check(CLI::ExistingFile);
  app.add_option("-o,--output", out, "Output triangle mesh (.msh); report beside it as .json")->required();
  app.add_option("--seed", opt.seed, "Random seed of the interior points")->capture_default_str();
  app.add_option("-p,--exponent", opt.p, "L_p exponent of the energy (eq. 4.1) and of eq. 4.12")
      ->capture_default_str()
      ->check(CLI::Range(2.0, 32.0));
  app.add_option("--scale", scale,
                 "Metric scale: M_eff = scale * M (default 0.25 for quadapt frames, 0.5 with "
                 "--convention philip, 1 for --analytic)");
  app.add_option("--convention", convention,
                 "Size convention of FRAME: quadapt (d = det M / 4, docs/design.md) or philip (the thesis's "
                 "files: full-edge sizes, d = det M, so M_quadapt = 2 M_philip)")
      ->capture_default_str()
      ->check(CLI::IsMember({"quadapt", "philip"}));
  app.add_option("--analytic", analytic, "Validation metric instead of FRAME: 'saddle' (eq. 6.1)")
      ->check(CLI::IsMember({"saddle"}));
  app.add_flag("--sampled", sampled, "With --analytic: sample the metric at the centres of a --grid grid");
  app.add_option("--grid", grid, "With --analytic: background grid size")->capture_default_str()->check(CLI::Range(1, 4096));
  app.add_option("--initial", opt.initial_points,
                 "Interior points to start from (default: the requested count for frames, 20 for --analytic)");
  app.add_option("--cells", cells_kind,
                 "Voronoi cells of the energy: metric (frames' default: distances in each background cell's metric, so the points form a square lattice in the metric at any frame orientation; docs/lpcvt.md) or euclidean (the thesis's; --analytic's default)")
      ->check(CLI::IsMember({"metric", "euclidean"}));
  app.add_option("--cell-anisotropy", cell_alpha,
                 "With --cells metric: the cells' anisotropy is the metric's to this power (1: the metric's own cells, best on constant frames; 0: Euclidean; 0.9, the default, keeps the constant-frame figures and is better on adaptive frames with extreme stretch: docs/lpcvt.md)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--init", init,
                 "Initial points: lattice (frames' default: the frame-aligned lattice grown from one seed), "
                 "multilevel (coarse levels from density seeds, each finer level from the children of the "
                 "coarser sites), density (random, by the metric's density) or uniform (random; --analytic's)")
      ->check(CLI::IsMember({"lattice", "multilevel", "density", "uniform"}));
  app.add_option("--coarse-points", opt.coarse_points, "Multilevel: interior points of the coarsest level, at least")
      ->capture_default_str()->check(PositiveValue);
  double complexity = 0;
  int degree = -1;
  app.add_option("--complexity", complexity,
                 "Target DOFs: rescale the frame uniformly so that the final all-quad mesh has "
                 "complexity/(degree+1)^2 cells (PHiLiP's frame files are normalised and carry no size)")
      ->check(PositiveValue);
  app.add_option("--degree", degree, "DG degree P for --complexity (cells = complexity/(P+1)^2)")->check(CLI::Range(0, 20));
  int smooth = 0;
  double gradation = 0;
  app.add_option("--smooth", smooth,
                 "Log-Euclidean smoothing of the metric M^T M across background cells: passes (0 = none)")
      ->capture_default_str()->check(CLI::Range(0, 1000));
  app.add_option("--gradation", gradation,
                 "Anisotropic size gradation of the metric: sizes grow at most by this factor per unit metric "
                 "length between neighbouring background cells (metric intersection; 0 = none); the point count is kept")
      ->capture_default_str();
  double cells_per_triangle = 2;
  app.add_option("--cells-per-triangle", cells_per_triangle,
                 "Final all-quad cells per lpcvt triangle that recombine gives (2 in theory: pairs, then a split "
                 "into 4; measured 1.92-2.01, docs/bench-lpcvt.md): the point count is sized by 2/R")
      ->capture_default_str()->check(CLI::Range(1.0, 3.0));
  std::string frame_out;
  app.add_option("--write-frame", frame_out,
                 "Also write the frame actually meshed (after --smooth/--gradation/--complexity) as Vinv in the "
                 "quadapt convention (4 M_eff), e.g. for meshquality --frame");
  bool no_exact = false;
  app.add_flag("--no-exact-count", no_exact,
               "Do not set the point count to the requested one (multilevel levels, before the final minimisation)");
  app.add_option("--max-cycles", opt.max_cycles, "Split/merge cycles at most")->capture_default_str()->check(PositiveValue);
  auto* omaxit = app.add_option("--max-iterations", opt.lbfgs.max_iterations,
                                 "L-BFGS iterations per minimisation at most (default 100 for frames, 500 with --analytic)")
                      ->check(PositiveValue);
  double gamma = -1;
  app.add_option("--weight", gamma,
                 "Energy weight |det M|^gamma (energy.hpp): 1 (frames' default) gives one point per unit metric "
                 "area in graded frames; 0 is the thesis's energy (--analytic's default)");
  app.add_flag("--precondition", opt.lbfgs.precondition, "Scale every site's variables by its local frame");
  auto* odelta = app.add_option("--delta", opt.lbfgs.delta,
                                "Stop when the energy falls by less than this (relative) over --past iterations "
                                "(default 1e-3 for frames, 1e-10 with --analytic)");
  auto* opast = app.add_option("--past", opt.lbfgs.past, "Iterations of the --delta test (default 10 for frames, 5 with --analytic)");
  app.add_option("--gtol", opt.lbfgs.gtol, "Gradient tolerance (per site, relative)")->capture_default_str();
  auto* olmin = app.add_option("--lmin", opt.split.lmin,
                               "Merge edges shorter than this (metric units, eq. 4.12; default 0.25, "
                               "0 with --analytic as thesis §6.1)");
  auto* olmax = app.add_option("--lmax", opt.split.lmax,
                               "Split edges longer than this (default 2, sqrt(2) with --analytic)");
  app.add_option("--change-tol", opt.change_tol, "Fraction of edges changed counted as settled")->capture_default_str();
  app.add_option("--ramp-after", opt.ramp_after,
                 "Cycles after which the settled fraction ramps up by 0.5% per cycle to 5% (thesis §4.5)")
      ->capture_default_str();
  app.add_option("--voronoi", voronoi_out, "Also write the initial and final clipped Voronoi diagrams (JSON)");
  app.add_flag("--strict", strict, "Exit code 1 when the optimiser stopped early (the mesh is written anyway)");

  return tool.run(argc, argv, [&] {
    if (in.empty() == analytic.empty()) throw InputError("", "give either FRAME.msh or --analytic saddle");
    if (!in.empty()) tool.input(in);
    tool.output(out);
    if (!voronoi_out.empty()) {
      tool.output(voronoi_out);
      namespace fs = std::filesystem;
      if (fs::path(voronoi_out).lexically_normal() == fs::path(tool.report_path()).lexically_normal() ||
          fs::path(voronoi_out).lexically_normal() == fs::path(out).lexically_normal())
        throw InputError("", "--voronoi " + voronoi_out + " would overwrite the mesh or the report");
    }
    if (!frame_out.empty()) {
      tool.output(frame_out);
      if (std::filesystem::path(frame_out).lexically_normal() == std::filesystem::path(out).lexically_normal())
        throw InputError("", "--write-frame " + frame_out + " would overwrite the mesh");
    }
    if (!(opt.split.lmin >= 0 && opt.split.lmax > opt.split.lmin))
      throw InputError("", "need 0 <= --lmin < --lmax");
    if ((complexity > 0) != (degree >= 0)) throw InputError("", "--complexity and --degree go together");
    opt.exact_count = !no_exact;
    if (analytic.empty()) {  // frames: a lattice start needs a short relaxation (docs/lpcvt.md, Convergence)
      if (!omaxit->count()) opt.lbfgs.max_iterations = 100;
      if (!odelta->count()) opt.lbfgs.delta = 1e-3;
      if (!opast->count()) opt.lbfgs.past = 10;
    }
    opt.lbfgs.gamma = gamma >= 0 ? gamma : (analytic.empty() ? 1.0 : 0.0);
    tool.option("weight", opt.lbfgs.gamma);

    std::unique_ptr<Background> bg;
    {
      auto ph = tool.phase("read");
      if (!analytic.empty()) {
        Mesh m = make_structured_quads(grid, grid, -1.3, 1.3, -1.3, 1.3);
        double s = scale > 0 ? scale : 1.0;
        auto f = std::make_shared<SaddleMetric>();
        bg = std::make_unique<Background>(sampled ? Background::sampled(m, *f, s) : Background::analytic(m, f, s));
        if (opt.initial_points < 0 && (init.empty() || init == "uniform" || init == "density")) opt.initial_points = 20;
        if (!olmin->count()) opt.split.lmin = 0;
        if (!olmax->count()) opt.split.lmax = std::sqrt(2.0);
        opt.seed_mode = init == "density" ? SeedMode::Density : init == "lattice" ? SeedMode::Lattice : SeedMode::Uniform;
        opt.multilevel = init == "multilevel";
        if (init != "multilevel" && init != "lattice") opt.exact_count = false;  // the thesis's procedure
        tool.option("metric", sampled ? "saddle sampled on " + std::to_string(grid) + "x" + std::to_string(grid) : "saddle");
      } else {
        Mesh m = read_valid_msh(in, ValidateOptions::fields({"Vinv"}));
        const double def = convention == "philip" ? 0.5 : 0.25;
        bg = std::make_unique<Background>(Background::from_frame(m, scale > 0 ? scale : def, in));
        opt.seed_mode = init == "uniform" ? SeedMode::Uniform
                        : (init.empty() || init == "lattice") ? SeedMode::Lattice
                                                                : SeedMode::Density;
        opt.multilevel = init == "multilevel";
        tool.option("metric", "frame Vinv");
      }
      if (smooth > 0 || gradation > 0) {
        if (!analytic.empty() && !sampled) throw InputError("", "--smooth/--gradation need a frame or --sampled");
        if (gradation != 0 && !(gradation > 1)) throw InputError("", "--gradation must be > 1");
        if (smooth > 0) {
          FilterReport f = smooth_metric(*bg, smooth);
          tool.report()["smoothing"] = {{"passes", smooth}, {"cells_changed", f.cells_changed}, {"rescale", f.rescale},
                                        {"max_neighbour_size_ratio_before", f.max_ratio_before},
                                        {"max_neighbour_size_ratio_after", f.max_ratio_after}};
          tool.log("metric smoothed (" + std::to_string(smooth) + " log-Euclidean passes): largest neighbour size ratio " +
                   sci(f.max_ratio_before) + " -> " + sci(f.max_ratio_after));
        }
        if (gradation > 0) {
          FilterReport f = grade_metric(*bg, gradation);
          tool.report()["gradation"] = {{"growth", gradation}, {"updates", f.passes}, {"cells_changed", f.cells_changed}, {"rescale", f.rescale},
                                        {"max_neighbour_size_ratio_before", f.max_ratio_before},
                                        {"max_neighbour_size_ratio_after", f.max_ratio_after}};
          tool.log("metric graded (growth " + sci(gradation) + " per unit length, " + std::to_string(f.passes) +
                   " updates): " + std::to_string(f.cells_changed) + " cells refined, largest neighbour size ratio " + sci(f.max_ratio_before) + " -> " +
                   sci(f.max_ratio_after));
        }
      }
      // Final all-quad cells the frame asks for: 4 x metric area of M_eff (docs/lpcvt.md, Sizes).
      const double frame_cells = 4 * bg->metric_area();
      tool.report()["frame_cells"] = frame_cells;
      if (complexity > 0) {
        const double target = complexity / ((degree + 1.0) * (degree + 1.0));
        const double f = std::sqrt(target / frame_cells);
        *bg = bg->scaled(f);
        tool.report()["complexity"] = complexity;
        tool.report()["degree"] = degree;
        tool.report()["metric_rescale"] = f;
        tool.log("--complexity " + sci(complexity) + " at degree " + std::to_string(degree) + ": " +
                 sci(target) + " final cells (the frame asks " + sci(frame_cells) +
                 "): metric scaled by " + sci(f));
      }
      tool.report()["target_cells"] = 4 * bg->metric_area();
      if (cells_per_triangle != 2) *bg = bg->scaled(std::sqrt(2 / cells_per_triangle));
      tool.report()["cells_per_triangle"] = cells_per_triangle;
      tool.option("metric_scale", bg->scale());
      if (cells_kind.empty()) cells_kind = analytic.empty() ? "metric" : "euclidean";
      bg->set_metric_cells(cells_kind == "metric", cell_alpha);
      tool.option("cells", cells_kind);
      tool.option("cell_anisotropy", cell_alpha);
    }
    LpcvtResult r;
    {
      auto ph = tool.phase("lpcvt");
      r = run_lpcvt(*bg, opt, [&](const std::string& s) { tool.log(s); });
    }
    TriangulationCheck chk = check_triangulation(r.mesh);
    if (!chk.ok()) throw NumericalError("lpcvt: invalid output triangulation: " + chk.summary());
    auto& rep = tool.report();
    {
      EnergyTimers et = energy_timers();
      rep["energy_seconds"] = {{"delaunay", et.delaunay}, {"integrate", et.integrate}, {"evaluations", et.evaluations}, {"updates", et.updates}, {"rebuilds", et.rebuilds}};
    }
    const nlohmann::json figures = report_json(r);
    for (auto& [k, v] : figures.items()) rep[k] = v;
    rep["area"] = chk.area;
    // recombine pairs the triangles and splits every quad into four: about 2 cells per triangle
    rep["expected_cells"] = cells_per_triangle * r.mesh.num_cells();
    rep["domain_area"] = bg->area();
    AngleStats am = triangle_angles(*bg, r.mesh, true);
    rep["largest_angle_metric_median"] = am.median_largest;
    rep["largest_angle_metric_80_100"] = am.frac_largest_80_100;
    AngleStats ap = triangle_angles(*bg, r.mesh, false);
    rep["largest_angle_median"] = ap.median_largest;
    rep["largest_angle_80_100"] = ap.frac_largest_80_100;
    AlignmentStats al = voronoi_alignment(*bg, r.sites, r.nfixed);
    rep["voronoi_alignment_mean_deg"] = al.mean_deviation;
    AlignmentStats alp = voronoi_alignment(*bg, r.sites, r.nfixed, true);
    rep["voronoi_principal_alignment_mean_deg"] = alp.mean_deviation;
    {
      auto ph = tool.phase("write");
      if (!voronoi_out.empty()) {
        nlohmann::json v;
        v["initial"] = voronoi_json(*bg, r.initial_sites, r.nfixed);
        v["final"] = voronoi_json(*bg, r.sites, r.nfixed);
        v["history"] = rep["history"];
        v["cycle_history"] = rep["cycle_history"];
        atomic_write(voronoi_out, [&](std::ostream& os) { os << v.dump() << "\n"; });
      }
      write_msh(r.mesh, out);
      if (!frame_out.empty()) {
        Mesh fm = bg->mesh();
        fm.clear_fields();
        CellField f;
        f.name = "Vinv";
        f.ncomp = 9;
        f.values.assign(static_cast<size_t>(fm.num_cells()) * 9, 0.0);
        for (int c = 0; c < fm.num_cells(); ++c) {
          const Mat2 M = 4 * bg->mesh_cell_metric(c);
          f(c, 0) = M(0, 0);
          f(c, 1) = M(0, 1);
          f(c, 3) = M(1, 0);
          f(c, 4) = M(1, 1);
          f(c, 8) = 1;
        }
        fm.cell_fields.push_back(f);
        write_msh(fm, frame_out);
      }
    }
    tool.log("largest triangle angles (median): " + sci(am.median_largest) + " deg in the metric, " +
             sci(ap.median_largest) + " deg in physical space; Voronoi edges off the metric axes by " +
             sci(al.mean_deviation) + " deg, off the principal directions by " +
             sci(alp.mean_deviation) + " deg (length-weighted means)");
    if (!r.converged) {
      tool.log("warning: not converged (" + r.stop + "); the mesh is valid but the points are not optimal");
      if (strict) throw PartialFailure("not converged: " + r.stop + " (mesh written)");
    }
  });
}
