#include "lpcvt/run.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>

#include "core/error.hpp"
#include "core/format.hpp"
#include "frame/bending.hpp"
#include "lpcvt/cross_field.hpp"
#include "lpcvt/energy.hpp"
#include "lpcvt/metric_filter.hpp"
#include "lpcvt/phases.hpp"
#include "lpcvt/point_quality.hpp"
#include "lpcvt/triangulate.hpp"

namespace quadapt::lpcvt {

LpcvtOptions LpcvtOptions::for_frame() {
  LpcvtOptions o;
  o.lbfgs.max_iterations = 300;
  o.lbfgs.delta = 1e-3;
  o.lbfgs.past = 10;
  // stop when the points have settled (RMS move over 10 iterations at most 5 % of the spacing)
  // or the mesh has (the edges' RMS change in the metric at most 5 % of the target edge): the
  // move also counts a drift of the whole point set, which changes no edge — at 1.1e6 points it
  // kept the minimisation going for twice the evaluations for the same mesh (docs/lpcvt.md
  // *Convergence*)
  o.lbfgs.move_tol = 0.05;
  o.lbfgs.edge_tol = 0.05;
  o.lbfgs.gamma = 1;
  o.lbfgs.precondition = true;  // fewer iterations to a settled mesh (docs/bench-lpcvt-history.md, "Second pass")
  o.boundary_norm = 0;          // = p: one wall point per lattice row (boundary_points.hpp)
  o.set_init("", false);
  return o;
}

LpcvtJob LpcvtJob::for_frame() {
  LpcvtJob j;
  j.lpcvt = LpcvtOptions::for_frame();
  j.metric_cells = true;
  j.smooth = 4;                // docs/lpcvt.md, Method 9 "Why smoothing 4 by default"
  j.gradation = 2.0;           // docs/lpcvt.md, Method 9 "Why gradation 2 by default"
  j.free_orientation = true;   // docs/lpcvt.md, Method 10
  return j;
}

LpcvtJob LpcvtJob::for_analytic() {
  LpcvtJob j;
  j.lpcvt = LpcvtOptions::for_analytic();
  j.metric_cells = false;
  j.smooth = 0;
  j.gradation = 0;
  j.free_orientation = false;
  return j;
}

LpcvtOptions LpcvtOptions::for_analytic() {
  LpcvtOptions o;
  o.lbfgs.gamma = 0;
  o.split.lmin = 0;
  o.split.lmax = std::sqrt(2.0);
  o.set_init("", true);
  return o;
}

void LpcvtOptions::set_init(const std::string& init, bool analytic) {
  multilevel = init == "multilevel";
  if (analytic) {
    seed_mode = init == "density" ? SeedMode::Density : init == "lattice" ? SeedMode::Lattice : SeedMode::Uniform;
    const bool random = init.empty() || init == "uniform" || init == "density";
    initial_points = random ? 20 : -1;
    if (init != "multilevel" && init != "lattice") exact_count = false;  // the thesis's procedure
  } else {
    seed_mode = init == "uniform" ? SeedMode::Uniform
                : (init.empty() || init == "lattice") ? SeedMode::Lattice
                                                        : SeedMode::Density;
    initial_points = -1;
  }
}

namespace {

void say(const std::function<void(const std::string&)>& log, const std::string& s) {
  if (log) log(s);
}

nlohmann::json filter_json(const FilterReport& f) {
  return {{"cells_changed", f.cells_changed}, {"rescale", f.rescale},
          {"max_neighbour_size_ratio_before", f.max_ratio_before}, {"max_neighbour_size_ratio_after", f.max_ratio_after}};
}

// Filters, complexity rescale and cells-per-triangle factor, common to both backgrounds.
void finish_background(Background& bg, const LpcvtJob& job, nlohmann::json& rep,
                       const std::function<void(const std::string&)>& log) {
  if (job.smooth > 0 || job.gradation > 0) {
    if (job.gradation != 0 && !(job.gradation > 1)) throw InputError("", "--gradation must be > 1");
    const FilterReports fr = filter_metric(bg, job.smooth, job.gradation);
    if (fr.smoothing) {
      const FilterReport& f = *fr.smoothing;
      rep["smoothing"] = filter_json(f);
      rep["smoothing"]["passes"] = job.smooth;
      say(log, "metric smoothed (" + std::to_string(job.smooth) + " log-Euclidean passes): largest neighbour size ratio " +
                   sci(f.max_ratio_before) + " -> " + sci(f.max_ratio_after));
    }
    if (fr.gradation) {
      const FilterReport& f = *fr.gradation;
      rep["gradation"] = filter_json(f);
      rep["gradation"]["growth"] = job.gradation;
      rep["gradation"]["updates"] = f.passes;
      say(log, "metric graded (growth " + sci(job.gradation) + " per unit length, " + std::to_string(f.passes) +
                   " updates): " + std::to_string(f.cells_changed) + " cells refined, largest neighbour size ratio " +
                   sci(f.max_ratio_before) + " -> " + sci(f.max_ratio_after));
    }
  }
  if (job.free_orientation) {
    const CrossFieldReport x = align_free_orientation(bg);
    rep["orientation"] = {{"mode", "boundary"}, {"free_cells", x.free_cells}, {"rotated_cells", x.rotated_cells},
                          {"mean_rotation_deg", x.mean_rotation_deg}, {"max_rotation_deg", x.max_rotation_deg}};
    if (x.free_cells > 0)
      say(log, "orientation: " + std::to_string(x.free_cells) + " nearly isotropic cells free, " +
                   std::to_string(x.rotated_cells) + " turned to the boundary-aligned cross field (mean " +
                   sci(x.mean_rotation_deg) + " deg, largest " + sci(x.max_rotation_deg) + " deg)");
  } else {
    rep["orientation"] = {{"mode", "frame"}};
  }
  // Final all-quad cells the background asks for (docs/lpcvt.md, Sizes).
  const double frame_cells = bg.metric_area() / (kSplit * kSplit);
  rep["frame_cells"] = frame_cells;
  if ((job.complexity > 0) != (job.degree >= 0)) throw InputError("", "--complexity and --degree go together");
  if (job.complexity > 0) {
    const double target = cells_for_complexity(job.complexity, job.degree);
    const double f = std::sqrt(target / frame_cells);
    bg = bg.scaled(f);
    rep["complexity"] = job.complexity;
    rep["degree"] = job.degree;
    rep["metric_rescale"] = f;
    say(log, "--complexity " + sci(job.complexity) + " at degree " + std::to_string(job.degree) + ": " +
                 sci(target) + " final cells (the frame asks " + sci(frame_cells) +
                 "): metric scaled by " + sci(f));
  }
  rep["target_cells"] = bg.metric_area() / (kSplit * kSplit);
  if (job.cells_per_triangle != 2) bg = bg.scaled(std::sqrt(2 / job.cells_per_triangle));
  rep["cells_per_triangle"] = job.cells_per_triangle;
  rep["options"]["metric_scale"] = bg.scale();
  bg.set_metric_cells(job.metric_cells, job.cell_anisotropy);
  rep["options"]["cells"] = job.metric_cells ? "metric" : "euclidean";
  rep["options"]["cell_anisotropy"] = job.cell_anisotropy;
}

}  // namespace

void check_job(const LpcvtJob& job) {
  const LpcvtOptions& o = job.lpcvt;
  const LbfgsOptions& l = o.lbfgs;
  const auto need = [](bool ok, const std::string& field, double v, const std::string& range) {
    if (ok) return;
    char value[32];
    std::snprintf(value, sizeof value, "%g", v);  // as the caller set it: 0, -3, nan
    throw InputError("", field + " = " + value + ": " + range);
  };
  const auto in = [](double v, double lo, double hi) { return v >= lo && v <= hi; };  // false for NaN
  need(in(o.p, 2, 32), "LpcvtOptions::p", o.p, "the L_p exponent must be in [2, 32] (lpcvt --lp-exponent)");
  need(LpcvtOptions::valid_boundary_norm(o.boundary_norm), "LpcvtOptions::boundary_norm", o.boundary_norm,
       "0 (the exponent p) or in [1, 64] (lpcvt --boundary-norm)");
  need(in(o.start_jitter, 0, 10), "LpcvtOptions::start_jitter", o.start_jitter, "in [0, 10] target edges (lpcvt --jitter)");
  need(o.coarse_points > 0, "LpcvtOptions::coarse_points", o.coarse_points, "positive (lpcvt --coarse-points)");
  need(o.max_cycles >= 1, "LpcvtOptions::max_cycles", o.max_cycles, "at least 1 (lpcvt --max-cycles)");
  need(in(o.change_tol, 0, 1), "LpcvtOptions::change_tol", o.change_tol, "in [0, 1] (lpcvt --change-tol)");
  need(o.ramp_after >= 0, "LpcvtOptions::ramp_after", o.ramp_after, "0 or more (lpcvt --ramp-after)");
  need(in(o.lattice_phase.x(), 0, 1) && o.lattice_phase.x() < 1, "LpcvtOptions::lattice_phase.x", o.lattice_phase.x(),
       "in [0, 1) (lpcvt --lattice-phase)");
  need(in(o.lattice_phase.y(), 0, 1) && o.lattice_phase.y() < 1, "LpcvtOptions::lattice_phase.y", o.lattice_phase.y(),
       "in [0, 1) (lpcvt --lattice-phase)");
  need(l.max_iterations >= 1, "LbfgsOptions::max_iterations", l.max_iterations, "at least 1 (lpcvt --max-iterations)");
  need(l.past >= 1, "LbfgsOptions::past", l.past, "at least 1 (lpcvt --past)");
  need(in(l.delta, 0, 1) && l.delta < 1, "LbfgsOptions::delta", l.delta, "in [0, 1) (lpcvt --delta)");
  need(in(l.gtol, 0, HUGE_VAL), "LbfgsOptions::gtol", l.gtol, "0 or more (lpcvt --gtol)");
  need(in(l.move_tol, 0, HUGE_VAL), "LbfgsOptions::move_tol", l.move_tol, "0 or more (lpcvt --move-tol)");
  need(in(l.edge_tol, 0, HUGE_VAL), "LbfgsOptions::edge_tol", l.edge_tol, "0 or more (lpcvt --edge-tol)");
  need(in(l.gamma, 0, HUGE_VAL), "LbfgsOptions::gamma", l.gamma, "0 or more (lpcvt --weight)");
  need(l.memory >= 1, "LbfgsOptions::memory", l.memory, "at least 1");
  need(job.scale == 0 || (job.scale > 0 && std::isfinite(job.scale)), "LpcvtJob::scale", job.scale,
       "0 (the default scale) or a positive number (lpcvt --scale)");
  need(in(job.smooth, 0, 1000), "LpcvtJob::smooth", job.smooth, "in [0, 1000] passes (lpcvt --smooth)");
  need(job.gradation == 0 || (job.gradation > 1 && std::isfinite(job.gradation)), "LpcvtJob::gradation", job.gradation,
       "0 (none) or above 1 (lpcvt --gradation)");
  need(in(job.cells_per_triangle, 1, 3), "LpcvtJob::cells_per_triangle", job.cells_per_triangle,
       "in [1, 3] (lpcvt --cells-per-triangle)");
  need(in(job.cell_anisotropy, 0, 1), "LpcvtJob::cell_anisotropy", job.cell_anisotropy, "in [0, 1] (lpcvt --cell-anisotropy)");
  need(in(job.phases, 0, 16), "LpcvtJob::phases", job.phases, "in [0, 16] (lpcvt --phases)");
  need(in(job.max_points, 0, HUGE_VAL), "LpcvtJob::max_points", job.max_points, "0 (no limit) or more (lpcvt --max-points)");
}

Background frame_background(const Frame& f, const LpcvtJob& job, nlohmann::json& report,
                            const std::function<void(const std::string&)>& log) {
  check_job(job);
  Background bg = Background::from_frame(f, job.scale > 0 ? job.scale : frame_metric_scale());
  report["options"]["metric"] = "frame Vinv";
  finish_background(bg, job, report, log);
  const FrameSpan span = frame_span(bg);
  const std::string warning = frame_span_warning(span);
  report["frame_span"] = {{"cells_across_long_axis", span.cells_across},
                          {"cells_along_chord", span.cells_along_chord},
                          {"stretch", span.stretch},
                          {"warning", warning.empty() ? nlohmann::json() : nlohmann::json(warning)}};
  // the bending of the frame lpcvt meshes (after --smooth and --gradation), in the frame's convention
  std::vector<Mat2> M(bg.mesh().num_cells());
  for (int c = 0; c < bg.mesh().num_cells(); ++c) M[c] = bg.mesh_cell_metric(c) / frame_metric_scale();
  const BendingSummary bend = summarize_bending(bg.mesh(), M, frame_bending(bg.mesh(), M));
  const std::string bend_warning = frame_bending_warning(bend.share_over_2, bend.max);
  report["frame_bending"] = {{"share_over_1", bend.share_over_1},
                             {"share_over_2", bend.share_over_2},
                             {"max", bend.max},
                             {"warning", bend_warning.empty() ? nlohmann::json() : nlohmann::json(bend_warning)}};
  return bg;
}

namespace {
/// The convex hull of the cells' vertices (Andrew's monotone chain): the domain's extent along any
/// direction is that of its hull, so each cell's extent costs the hull's few vertices.
std::vector<Vec2> vertex_hull(const Mesh& m) {
  std::vector<Vec2> p;
  for (const Cell& c : m.cells)
    for (int k = 0; k < c.nv; ++k) p.push_back(m.nodes[c.v[k]]);
  std::sort(p.begin(), p.end(), [](const Vec2& a, const Vec2& b) { return a.x() != b.x() ? a.x() < b.x() : a.y() < b.y(); });
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3) return p;
  std::vector<Vec2> h(2 * p.size());
  size_t k = 0;
  auto turn = [](const Vec2& o, const Vec2& a, const Vec2& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
  };
  for (size_t i = 0; i < p.size(); ++i) {  // lower hull
    while (k >= 2 && turn(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (size_t i = p.size() - 1, t = k + 1; i-- > 0;) {  // upper hull
    while (k >= t && turn(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  h.resize(k - 1);
  return h;
}
}  // namespace

namespace {
/// The length of the line x = c + t v inside the convex CCW polygon `hull` (0 when it misses it).
double hull_chord(const std::vector<Vec2>& hull, const Vec2& c, const Vec2& v) {
  if (hull.size() < 3) return 0;
  double lo = -std::numeric_limits<double>::infinity(), hi = -lo;
  for (size_t k = 0; k < hull.size(); ++k) {
    const Vec2& a = hull[k];
    const Vec2 e = hull[(k + 1) % hull.size()] - a;
    const Vec2 n(e.y(), -e.x());  // outward for a counter-clockwise hull: inside n . (x - a) <= 0
    const double nv = n.dot(v), nc = n.dot(c - a);
    if (nv > 0)
      hi = std::min(hi, -nc / nv);
    else if (nv < 0)
      lo = std::max(lo, -nc / nv);
    else if (nc > 0)
      return 0;
  }
  return std::max(0.0, hi - lo);
}
}  // namespace

std::string frame_bending_warning(double share_over_2, double max) {
  if (!(share_over_2 > kBendingWarningShare)) return "";
  return "the frame's rows bend fast: on " + std::to_string(std::lround(100 * share_over_2)) +
         " % of its cells the long axis turns by more than its stretch allows (bending number kappa h1^2/h2 > 2, "
         "up to " + sci(max) + "; docs/quad-quality.md, \"Curved anisotropy\"): lpcvt takes the metric as constant "
         "over a cell, so such rows come out broken (quads across the layer, irregular vertices); ask for cells "
         "shorter along the curved layer (h1) or a lower stretch there, so that kappa h1^2/h2 <= 1";
}

FrameSpan frame_span(const Background& bg) {
  const Mesh& m = bg.mesh();
  const std::vector<Vec2> hull = vertex_hull(m);
  struct Span {
    double across, stretch, weight, chord;
  };
  std::vector<Span> cells;
  double total = 0;
  for (int c = 0; c < m.num_cells(); ++c) {
    const Mat2 M = bg.mesh_cell_metric(c) / frame_metric_scale();
    // M^T M = V^-T V^-1: its small eigenvalue 1/h1^2 along the long axis v, its large one 1/h2^2
    const Eigen::SelfAdjointEigenSolver<Mat2> eig(M.transpose() * M);
    const double h1 = 1 / std::sqrt(eig.eigenvalues()(0)), h2 = 1 / std::sqrt(eig.eigenvalues()(1));
    const Vec2 v = eig.eigenvectors().col(0);
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const Vec2& x : hull) {
      lo = std::min(lo, v.dot(x));
      hi = std::max(hi, v.dot(x));
    }
    const double w = cell_area(m, c) * std::abs(M.determinant());
    cells.push_back({(hi - lo) / (2 * h1), h1 / h2, w, hull_chord(hull, cell_centroid(m, c), v) / (2 * h1)});
    total += w;
  }
  auto median = [&](double Span::*f) {
    std::sort(cells.begin(), cells.end(), [&](const Span& a, const Span& b) { return a.*f < b.*f; });
    double acc = 0;
    for (const Span& c : cells)
      if ((acc += c.weight) >= total / 2) return c.*f;
    return cells.empty() ? 0.0 : cells.back().*f;
  };
  FrameSpan s;
  s.cells_across = median(&Span::across);
  s.stretch = median(&Span::stretch);
  s.cells_along_chord = median(&Span::chord);
  return s;
}

std::string frame_span_warning(const FrameSpan& s) {
  if (!(s.cells_across < kMinCellsAcross)) {
    if (!(s.cells_along_chord < kMinCellsAlongChord) || !(s.stretch >= kMinRowStretch)) return "";
    return "the frame asks for only " + sci(s.cells_along_chord) +
           " cells along its long axis across the domain (stretch " + sci(s.stretch) + "), fewer than " +
           sci(kMinCellsAlongChord) +
           ": lpcvt's points are two cells apart, so rows that short cannot keep the frame's lengths (a row gets "
           "an even number of cells) — expect edges outside the frame's range and irregular vertices; ask for "
           "cells shorter along the long axis (h1) or a lower stretch";
  }
  return "the frame asks for only " + sci(s.cells_across) + " cells across the domain along its long axis (stretch " +
         sci(s.stretch) + "), fewer than " + sci(kMinCellsAcross) +
         ": lpcvt's points are two cells apart, so all or nearly all of them lie on the boundary and every cell "
         "reaches from wall to wall (a degenerate mesh, which cannot follow the frame); ask for cells shorter along "
         "the long axis (h1), or check the frame's size convention (--convention) and --complexity";
}

Background saddle_background(int grid, bool sampled, const LpcvtJob& job, nlohmann::json& report,
                             const std::function<void(const std::string&)>& log) {
  check_job(job);
  if (grid < 1) throw InputError("", "--grid must be positive");
  const Mesh m = make_structured_quads(grid, grid, -1.3, 1.3, -1.3, 1.3);
  const double s = job.scale > 0 ? job.scale : 1.0;
  auto f = std::make_shared<SaddleMetric>();
  Background bg = sampled ? Background::sampled(m, *f, s) : Background::analytic(m, f, s);
  report["options"]["metric"] = sampled ? "saddle sampled on " + std::to_string(grid) + "x" + std::to_string(grid) : "saddle";
  if ((job.smooth > 0 || job.gradation > 0) && !sampled) throw InputError("", "--smooth/--gradation need a frame or --sampled");
  finish_background(bg, job, report, log);
  return bg;
}

void check_point_budget(const Background& bg, const LpcvtJob& job, const std::string& path) {
  const double n = bg.metric_area();
  if (job.max_points > 0 && !(n <= job.max_points))
    throw InputError(path, "the frame asks for " + sci(n) + " points, more than --max-points " + sci(job.max_points) +
                               " (about 1.4 kB of memory each); check its size convention (--convention), --complexity "
                               "and --scale, or raise --max-points");
}

int auto_phases(double metric_area, double spread) {
  return metric_area <= kAutoPhasePoints && spread <= kAutoPhaseSpread ? kAutoPhases : 1;
}

int auto_phases(const Background& bg) { return auto_phases(bg.metric_area(), metric_spread(bg)); }

LpcvtResult mesh_background(const Background& bg, const LpcvtJob& job, nlohmann::json& rep,
                            const std::function<void(const std::string&)>& log) {
  const LpcvtOptions& opt = job.lpcvt;
  check_job(job);
  check_point_budget(bg, job, "");
  if (!(opt.split.lmin >= 0 && opt.split.lmax > opt.split.lmin)) throw InputError("", "need 0 <= --lmin < --lmax");
  rep["options"]["weight"] = opt.lbfgs.gamma;
  const bool lattice = opt.seed_mode == SeedMode::Lattice && !opt.multilevel && !bg.is_analytic();
  const bool automatic = lattice && job.phases <= 0;
  const double spread = automatic ? metric_spread(bg) : 0;
  const int phases = !lattice ? 1 : automatic ? auto_phases(bg.metric_area(), spread) : job.phases;
  rep["options"]["phases"] = phases;
  if (automatic) rep["metric_spread"] = spread;  // what auto decided on
  // the effective start and preconditioning (their defaults differ between frames and --analytic)
  rep["options"]["init"] = opt.multilevel ? "multilevel"
                           : opt.seed_mode == SeedMode::Lattice ? "lattice"
                           : opt.seed_mode == SeedMode::Density ? "density"
                                                                : "uniform";
  rep["options"]["precondition"] = opt.lbfgs.precondition;
  LpcvtResult r;
  if (phases == 1) {
    r = run_lpcvt(bg, opt, log);
  } else {
    PhaseRuns pr = run_phases(bg, opt, phases, log);
    r = std::move(pr.best);
    rep["phases"] = std::move(pr.runs);
    rep["phase"] = pr.kept;
  }
  const TriangulationCheck chk = check_triangulation(r.mesh);
  if (!chk.ok()) throw NumericalError("invalid output triangulation: " + chk.summary());
  const EnergyTimers& et = r.energy_timers;
  rep["energy_seconds"] = {{"delaunay", et.delaunay}, {"integrate", et.integrate}, {"evaluations", et.evaluations},
                           {"updates", et.updates}, {"rebuilds", et.rebuilds}, {"metric_graph_carried", et.carried},
                           {"site_tree_refits", et.tree_refits}, {"security_grid_searches", et.grid_searches},
                           {"security_box_queries", et.box_queries}, {"security_box_hits", et.box_hits},
                           {"security_ellipse_queries", et.ellipse_queries}};
  const nlohmann::json figures = to_json(r);
  for (auto& [k, v] : figures.items()) rep[k] = v;
  rep["area"] = chk.area;
  // recombine pairs the triangles and splits every quad into four: about 2 cells per triangle
  rep["expected_cells"] = job.cells_per_triangle * r.mesh.num_cells();
  rep["domain_area"] = bg.area();
  const AngleStats am = triangle_angles(bg, r.mesh, true), ap = triangle_angles(bg, r.mesh, false);
  rep["largest_angle_metric_median"] = am.median_largest;
  rep["largest_angle_metric_80_100"] = am.frac_largest_80_100;
  rep["largest_angle_median"] = ap.median_largest;
  rep["largest_angle_80_100"] = ap.frac_largest_80_100;
  const std::array<AlignmentStats, 2> als = voronoi_alignments(bg, r.sites, r.nfixed);
  const AlignmentStats &al = als[0], &alp = als[1];
  rep["voronoi_alignment_mean_deg"] = al.mean_deviation;
  rep["voronoi_principal_alignment_mean_deg"] = alp.mean_deviation;
  say(log, "largest triangle angles (median): " + sci(am.median_largest) + " deg in the metric, " +
               sci(ap.median_largest) + " deg in physical space; Voronoi edges off the metric axes by " +
               sci(al.mean_deviation) + " deg, off the principal directions by " +
               sci(alp.mean_deviation) + " deg (length-weighted means)");
  return r;
}

Frame meshed_frame(const Background& bg) {
  Frame f;
  f.mesh = bg.mesh();
  f.mesh.clear_fields();
  f.M.resize(f.mesh.num_cells());
  for (int c = 0; c < f.mesh.num_cells(); ++c) f.M[c] = bg.mesh_cell_metric(c) / frame_metric_scale();
  return f;
}

nlohmann::json voronoi_report(const Background& bg, const LpcvtResult& r, const nlohmann::json& report) {
  nlohmann::json v;
  v["tool"] = "lpcvt";  // a rerun's --voronoi replaces this file, never one of the user's (Tool::output_json)
  v["content"] = "voronoi";
  v["initial"] = voronoi_json(bg, r.initial_sites, r.nfixed);
  v["final"] = voronoi_json(bg, r.sites, r.nfixed);
  v["history"] = report["history"];
  v["cycle_history"] = report["cycle_history"];
  return v;
}

}  // namespace quadapt::lpcvt
