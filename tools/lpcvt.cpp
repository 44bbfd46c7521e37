// lpcvt: points by L_p-CVT energy minimisation conforming to a frame field, then a constrained
// Delaunay triangulation (thesis ch. 4, Algorithms 1-3). See docs/lpcvt.md; the work is
// lib/lpcvt/run.hpp.
#include <cmath>
#include <cstring>
#include <string>

#include "cli/parse_errors.hpp"
#include "cli/tool.hpp"
#include "core/atomic_file.hpp"
#include "core/format.hpp"
#include "dg/degree.hpp"
#include "io/msh.hpp"
#include "gmsh/geometry.hpp"
#include "lpcvt/run.hpp"
#include "quad/mesh_utils.hpp"

int main(int argc, char** argv) {
  using namespace quadapt;
  using namespace quadapt::lpcvt;
  Tool tool("lpcvt", "Triangles whose points minimise the L_p-CVT energy of a frame field",
            "Reads FRAME.msh (per-cell 'Vinv', M = V^-1; its $FrameConvention says the size convention, none = "
            "PHiLiP's full-edge sizes), meshes the boundary by equidistribution in the metric (thesis eqs. "
            "4.2-4.7), seeds interior points, then repeats { L-BFGS on the L_p-CVT energy (eq. 4.1, gradient "
            "eqs. 4.8-4.11); split long / merge short edges (eq. 4.12) } until fewer than 2% of the edges change "
            "in two consecutive cycles, and writes the constrained Delaunay triangulation with the boundary "
            "groups. Points are two target cell edges apart, so 'recombine' (pairs + split into 4) gives the "
            "frame's cells. --analytic saddle: the thesis's validation (eq. 6.1 on [-1.3,1.3]^2). Report: points, "
            "iterations, energy, convergence history; an optimiser that stops early still writes a valid mesh "
            "(\"converged\": false; --strict: exit code 1). See docs/lpcvt.md.");
  bool analytic_mode = false;  // the defaults depend on the mode (LpcvtOptions::for_frame / for_analytic)
  for (int i = 1; i < argc; ++i) analytic_mode |= std::strncmp(argv[i], "--analytic", 10) == 0;
  LpcvtJob job = analytic_mode ? LpcvtJob::for_analytic() : LpcvtJob::for_frame();
  LpcvtOptions& opt = job.lpcvt;
  std::string in, out, analytic, voronoi_out, init, convention = "auto", frame_out, cells_kind, geometry;
  int grid = 16, initial = -1;
  bool sampled = false, strict = false, no_exact = false;
  auto& app = tool.app();
  app.add_option("FRAME", in, "Background mesh with the cell field Vinv (.msh)")->check(CLI::ExistingFile);
  app.add_option("-o,--output", out, "Output triangle mesh (.msh); report beside it as .json")->required();
  app.add_option("--seed", opt.seed, "Random seed of the start: the points of --init density|uniform, the moves of "
                 "--jitter (the lattice start without --jitter has no randomness)")->capture_default_str();
  app.add_option("--jitter", opt.start_jitter, "Lattice start: move each interior point by up to this many target "
                 "edges (in the metric) at random (--seed); 0 = the lattice as built")
      ->capture_default_str()->check(CLI::Range(0.0, 10.0));
  app.add_option("--phases", job.phases, "Lattice start: run from this many lattice phases (translations of the "
                 "lattice against walls oblique to the frame) and keep the one whose recombined mesh has the fewest "
                 "irregular interior vertices (docs/lpcvt.md, Method 11); 1 = one run; 0 = auto: 6 when the frame is constant "
                 "(the report's metric_spread <= 0.1) and asks for at most 4000 points, else 1 (on a graded frame the "
                 "rows bend and the phases are a lottery that costs 3.6x the time)")
      ->capture_default_str()->check(CLI::Range(0, 16));
  std::vector<double> lattice_phase;
  app.add_option("--lattice-phase", lattice_phase, "Lattice start: move the lattice by these fractions of a lattice cell "
                 "(two numbers in [0, 1)) along the axes the walls do not register — a single phase, e.g. the one a "
                 "--phases run reports as kept")
      ->expected(2);  // each in [0, 1): lib/cli/option_ranges.cpp (1 is phase 0 again)
  app.add_option("--lp-exponent", opt.p, "L_p exponent p of the energy (eq. 4.1) and of eq. 4.12")
      ->capture_default_str()->check(CLI::Range(2.0, 32.0));
  app.add_option("--boundary-norm", opt.boundary_norm, "q of the wall points' metric length |M tau|_q: 2 = the thesis's "
                 "eq. 4.2 (--analytic's default); 0 = the L_p exponent (frames' default), which puts one wall point on every "
                 "lattice row that crosses an oblique wall (docs/lpcvt.md, Method 2)")
      ->capture_default_str()
      ->check(CLI::Validator(
          [](std::string& s) -> std::string {
            double q = -1;
            try {
              q = std::stod(s);
            } catch (...) {
            }
            return LpcvtOptions::valid_boundary_norm(q) ? "" : s + " is neither 0 (the L_p exponent) nor in [1, 64]";
          },
          "0 or [1, 64]"));
  app.add_option("--scale", job.scale, "Metric scale: M_eff = scale * M, M in the quadapt convention (default 0.25; 1 for --analytic)");
  app.add_option("--convention", convention, "Size convention of FRAME: auto (the file's), quadapt or philip")
      ->capture_default_str()->check(CLI::IsMember({"auto", "quadapt", "philip"}));
  app.add_option("--analytic", analytic, "Validation metric instead of FRAME: 'saddle' (eq. 6.1)")->check(CLI::IsMember({"saddle"}));
  app.add_flag("--sampled", sampled, "With --analytic: sample the metric at the centres of a --grid grid");
  app.add_option("--grid", grid, "With --analytic: background grid size")->capture_default_str()->check(CLI::Range(1, 4096));
  app.add_option("--initial", initial, "Interior points to start from (default: the requested count for frames, 20 for --analytic)");
  app.add_option("--cells", cells_kind, "Voronoi cells of the energy: metric (frames' default: distances in each "
                 "background cell's metric; docs/lpcvt.md) or euclidean (the thesis's; --analytic's default)")
      ->check(CLI::IsMember({"metric", "euclidean"}));
  app.add_option("--cell-anisotropy", job.cell_anisotropy, "With --cells metric: the cells' anisotropy is the metric's "
                 "to this power (1: the metric's own cells; 0: Euclidean; docs/lpcvt.md)")
      ->capture_default_str()->check(CLI::Range(0.0, 1.0));
  app.add_option("--init", init, "Initial points: lattice (frames' default: frame-aligned, grown from one seed), "
                 "multilevel (coarse to fine), density (random by the metric) or uniform (random; --analytic's)")
      ->check(CLI::IsMember({"lattice", "multilevel", "density", "uniform"}));
  app.add_option("--coarse-points", opt.coarse_points, "Multilevel: interior points of the coarsest level, at least")
      ->capture_default_str()->check(PositiveValue);
  app.add_option("--complexity", job.complexity, "Target DOFs: the frame rescaled to complexity/(degree+1)^2 cells");
  app.add_option("--degree", job.degree, "DG degree P for --complexity (cells = complexity/(P+1)^2)")->check(CLI::Range(kMinDegree, kMaxDegree));
  app.add_option("--smooth", job.smooth, "Log-Euclidean smoothing of the metric M^T M across background cells: passes (0 = none; frames' default 4, --analytic's 0)")
      ->capture_default_str()->check(CLI::Range(0, 1000));
  app.add_option("--gradation", job.gradation, "Anisotropic size gradation: growth per unit metric length between "
                 "neighbouring background cells (0 = none; frames' default 2, --analytic's 0); the point count is kept")
      ->capture_default_str();  // the mode's default, recorded in the report's options
  std::string orientation = job.free_orientation ? "boundary" : "frame";
  app.add_option("--orientation", orientation, "Lattice orientation where the frame is nearly isotropic (stretch < 1.5): "
                 "boundary (frames' default: a cross field aligned with the walls and the anisotropic cells; the "
                 "metric M^T M is unchanged) or frame (the frame's own angle everywhere)")
      ->capture_default_str()->check(CLI::IsMember({"boundary", "frame"}));
  app.add_option("--cells-per-triangle", job.cells_per_triangle, "Final all-quad cells per triangle that recombine "
                 "gives (2 in theory; 1.92-2.01 measured): the point count is sized by 2/R")
      ->capture_default_str()->check(CLI::Range(1.0, 3.0));
  app.add_option("--max-points", job.max_points, "Refuse a frame that asks for more points than this (0 = no "
                 "limit; ~1.4 kB of memory per point): a frame far beyond it is nearly always a size-convention "
                 "or --complexity mistake")
      ->capture_default_str()
      ->check(NonNegativeValue);
  app.add_option("--write-frame", frame_out, "Also write the frame actually meshed (after filters and --complexity)");
  app.add_flag("--no-exact-count", no_exact, "Do not set the point count to the requested one (adjust_count)");
  app.add_option("--max-cycles", opt.max_cycles, "Split/merge cycles at most")->capture_default_str()->check(PositiveValue);
  app.add_option("--max-iterations", opt.lbfgs.max_iterations, "L-BFGS iterations per minimisation at most (500 with --analytic)")
      ->capture_default_str();  // >= 1: lib/cli/option_ranges.cpp's row for every tool
  app.add_option("--weight", opt.lbfgs.gamma, "Energy weight |det M|^gamma: 1 = one point per unit metric area in "
                 "graded frames; 0 = the thesis's energy (--analytic's default)")->capture_default_str();
  app.add_flag("--precondition", opt.lbfgs.precondition, "Scale every site's variables by its local frame (frames' "
               "default; --precondition=false: off, --analytic's default)");
  app.add_option("--delta", opt.lbfgs.delta, "Stop when the energy falls by less than this (relative) over --past iterations (1e-10 with --analytic)")
      ->capture_default_str();
  app.add_option("--past", opt.lbfgs.past, "Iterations of the --delta, --move-tol and --edge-tol tests (5 with --analytic)")->capture_default_str();
  app.add_option("--move-tol", opt.lbfgs.move_tol, "Stop when the points moved by less than this over --past iterations "
                 "(RMS, in units of the local point spacing; 0 = off, --analytic's default)")->capture_default_str();
  app.add_option("--edge-tol", opt.lbfgs.edge_tol, "Stop when the mesh has settled: the edges between neighbouring "
                 "points changed by less than this over --past iterations (RMS change of the edge vectors in the "
                 "metric, in target edges; a drift of the whole point set does not count; whichever of --move-tol and "
                 "--edge-tol holds first stops; 0 = off, --analytic's default)")
      ->capture_default_str();
  app.add_option("--gtol", opt.lbfgs.gtol, "Gradient tolerance (per site, relative)")->capture_default_str();
  app.add_option("--lmin", opt.split.lmin, "Merge edges shorter than this (metric units, eq. 4.12; 0 with --analytic)")->capture_default_str();
  app.add_option("--lmax", opt.split.lmax, "Split edges longer than this (sqrt(2) with --analytic)")->capture_default_str();
  app.add_option("--change-tol", opt.change_tol, "Fraction of edges changed counted as settled")->capture_default_str();
  app.add_option("--ramp-after", opt.ramp_after, "Cycles after which the settled fraction ramps up by 0.5% per cycle to 5% (thesis §4.5)")
      ->capture_default_str();
  app.add_option("--voronoi", voronoi_out, "Also write the initial and final clipped Voronoi diagrams (JSON)");
  app.add_option("--geometry", geometry, "The domain's true boundary (.geo, .brep, .step; named physical curves): boundary "
                 "points on its curves, equidistributed in the metric, and its names as the boundary groups (docs/curved.md)")
      ->check(CLI::ExistingFile);
  app.add_flag("--strict", strict, "Exit code 1 when the optimiser stopped early (the mesh is written anyway)");

  return tool.run(argc, argv, [&] {
    if (in.empty() == analytic.empty()) throw InputError("", "give either FRAME.msh or --analytic saddle");
    // refused before any work (run.cpp checks it again for the library's callers)
    if ((app.count("--complexity") > 0) != (app.count("--degree") > 0))
      throw InputError("", "--complexity and --degree go together: the frame is rescaled to complexity/(P+1)^2 cells");
    // an option of another mode or start is refused, not ignored (it gave the bytes of the run
    // without it, exit 0; a new-user review): as quadsmooth's --walls and recombine's --pairing are
    const std::string start = !init.empty() ? init : analytic_mode ? "uniform" : "lattice";
    const bool lattice_start = start == "lattice";
    const bool metric_cells = cells_kind.empty() ? job.metric_cells : cells_kind == "metric";
    const auto refuse = [&](const char* option, bool given, const std::string& why) {
      if (given) throw InputError("", std::string(option) + " " + why);
    };
    refuse("--sampled", sampled && !analytic_mode, "applies to --analytic only (a FRAME is its own cells)");
    refuse("--grid", app.count("--grid") > 0 && !analytic_mode, "applies to --analytic only (a FRAME is its own cells)");
    refuse("--convention", app.count("--convention") > 0 && analytic_mode,
           "applies to a FRAME's sizes; the --analytic metric has none to read");
    refuse("--coarse-points", app.count("--coarse-points") > 0 && start != "multilevel",
           "applies to --init multilevel only (the start is --init " + start + ")");
    refuse("--jitter", opt.start_jitter > 0 && !lattice_start,
           "moves the lattice start's points; the start is --init " + start + " (random already: give --seed)");
    refuse("--lattice-phase", !lattice_phase.empty() && !lattice_start,
           "moves the lattice start; the start is --init " + start);
    refuse("--phases", job.phases > 1 && (!lattice_start || analytic_mode),
           analytic_mode ? "applies to a FRAME's lattice start, not to --analytic"
                         : "applies to the lattice start; the start is --init " + start);
    refuse("--cell-anisotropy", app.count("--cell-anisotropy") > 0 && !metric_cells,
           "applies to --cells metric only (the cells are Euclidean here)");
    if (!in.empty()) tool.input(in);
    if (!geometry.empty()) tool.input(geometry);
    tool.output_mesh(out);
    if (!voronoi_out.empty()) tool.output_json(voronoi_out, "--voronoi");
    if (!frame_out.empty()) tool.output_mesh(frame_out);
    opt.exact_count = !no_exact;
    if (!lattice_phase.empty()) {
      if (app.count("--phases") && job.phases > 1) throw InputError("", "--lattice-phase gives one phase: it does not go with --phases > 1");
      opt.lattice_phase = Vec2(lattice_phase[0], lattice_phase[1]);
      job.phases = 1;
    }
    if (analytic_mode && app.count("--orientation") && orientation == "boundary")
      throw InputError("", "--orientation boundary needs a frame: the --analytic metric states its own orientation");
    job.free_orientation = orientation == "boundary";
    opt.set_init(init, analytic_mode);
    if (initial >= 0) opt.initial_points = initial;
    // a start count of its own is the thesis's procedure: split/merge finds the count, which is then
    // not set to the request (it was silent: 70 points for 107 asked, "converged"; a docs audit)
    const bool exact = opt.exact_count && opt.initial_points < 0;
    if (initial >= 0 && !no_exact && !analytic_mode)
      tool.log("--initial " + std::to_string(initial) +
               ": the point count is left to split/merge (the thesis's procedure), not set to the request; "
               "without --initial it is exact");
    tool.option("exact_count", exact);
    if (!cells_kind.empty()) job.metric_cells = cells_kind == "metric";
    const auto log = [&](const std::string& s) { tool.log(s); };
    Background bg;
    std::unique_ptr<BoundaryGeometry> g;
    {
      auto ph = tool.phase("read");
      if (!geometry.empty()) {
        g = open_geometry(geometry);
        opt.geometry = g.get();
        tool.option("geometry", geometry);
      }
      if (analytic_mode) {
        bg = saddle_background(grid, sampled, job, tool.report(), log);
      } else {
        const Frame f = read_frame(in, convention == "auto" ? std::nullopt : std::optional(parse_size_convention(convention)));
        check_simple_boundary(f.mesh, in);  // a pinched domain: named here, not as a broken output
        tool.option("convention", to_string(f.source));
        bg = frame_background(f, job, tool.report(), log);
        check_point_budget(bg, job, in);
        for (const char* key : {"frame_span", "frame_bending"})
          if (const auto& w = tool.report()[key]["warning"]; w.is_string()) tool.warn(in + ": " + w.get<std::string>());
      }
    }
    LpcvtResult r;
    {
      auto ph = tool.phase("lpcvt");
      try {
        r = mesh_background(bg, job, tool.report(), log);
      } catch (const NumericalError& e) {  // the frame's domain is what failed: named, as InputErrors are
        throw NumericalError((in.empty() ? std::string("--analytic ") + analytic : in) + ": " + e.what());
      }
    }
    {
      auto ph = tool.phase("write");
      // all or nothing: a side output that fails leaves the mesh (and the others) as they were
      OutputBatch batch;
      if (!voronoi_out.empty())
        batch.add(voronoi_out, [&](std::ostream& os) { os << voronoi_report(bg, r, tool.report()).dump() << "\n"; });
      write_msh(r.mesh, out, batch);
      if (!frame_out.empty()) write_frame(meshed_frame(bg), frame_out, batch);
      batch.commit();
    }
    // a frame that cannot be met on this domain (an element longer than the domain is wide, in
    // some direction) gives a count far from the frame's: say so, the report alone is easy to miss
    const double target = tool.report().value("target_cells", 0.0);
    const double expected = tool.report().value("expected_cells", 0.0);
    if (target > 0 && (expected > 1.5 * target || expected < target / 1.5))
      tool.warn("about " + count_text(expected) + " cells after recombine for the frame's " + count_text(target) +
               " (ratio " + sci(expected / target) +
               "): the frame's sizes cannot be met on this domain (elements longer than the domain in some direction?)");
    if (r.metric_flips_capped)
      tool.warn("the output's metric flips stopped at their cap (" + std::to_string(r.metric_flips) +
               "): the triangles are not Delaunay in the frame's metric (a frame stretched far beyond 1000:1?)");
    if (!r.converged) {
      tool.warn("not converged (" + r.stop + "); the mesh is valid but the points are not optimal");
      if (strict) throw PartialFailure("not converged: " + r.stop + " (mesh written)");
    }
  });
}
