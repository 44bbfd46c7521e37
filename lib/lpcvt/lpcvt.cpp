#include "lpcvt/lpcvt.hpp"

#include <cstdlib>

#include <algorithm>
#include <random>
#include <chrono>
#include <memory>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/error.hpp"
#include "frame/frame.hpp"
#include "lpcvt/delaunay.hpp"
#include "lpcvt/geometry_boundary.hpp"
#include "lpcvt/lattice.hpp"
#include "lpcvt/multilevel.hpp"
#include "lpcvt/rvd.hpp"
#include "lpcvt/triangulate.hpp"

namespace quadapt::lpcvt {

namespace {

// Split/merge cycles stop when the point count leaves [1/kCountGuard, kCountGuard] x the request
// (run_lpcvt, below).
constexpr double kCountGuard = 1.5;

// LpcvtOptions::start_jitter: x += M^-1 u, u uniform in the disk of radius r (metric units), the
// metric M of the background cell at x; moves leaving the domain are not made.
void jitter_start(const Background& bg, std::vector<Vec2>& pts, double r, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  int hint = -1;
  for (Vec2& x : pts) {
    const double rho = r * std::sqrt(U(rng)), phi = 2 * M_PI * U(rng);
    const int c = bg.locate(x, hint);
    if (c < 0) continue;
    hint = c;
    const Vec2 y = x + bg.cell(c).M.inverse() * Vec2(rho * std::cos(phi), rho * std::sin(phi));
    if (bg.locate(y, c) >= 0) x = y;
  }
}

std::string fmt(const char* f, double a) {
  char b[64];
  std::snprintf(b, sizeof b, f, a);
  return b;
}
}  // namespace

LpcvtResult run_lpcvt(const Background& bg, const LpcvtOptions& opt,
                      const std::function<void(const std::string&)>& log) {
  auto say = [&](const std::string& s) {
    if (log) log(s);
  };
  using Clock = std::chrono::steady_clock;
  LpcvtResult r;
  // Boundary (§4.2).
  const auto curves = opt.geometry ? std::vector<BoundaryCurve>{} : boundary_curves(bg, opt.corner_angle);
  Mesh groups;  // the output's boundary groups and domain name: the background's or the geometry's
  groups.domain_name = bg.mesh().domain_name;
  groups.domain_tag = bg.mesh().domain_tag;
  groups.groups = bg.mesh().groups;
  if (!LpcvtOptions::valid_boundary_norm(opt.boundary_norm))
    throw InputError("", "boundary_norm " + std::to_string(opt.boundary_norm) + " is neither 0 (the L_p exponent) nor in [1, 64]");
  const double q = opt.boundary_norm > 0 ? opt.boundary_norm : opt.p;
  auto boundary_of = [&](const Background& b) {
    return opt.geometry ? geometry_boundary(b, *opt.geometry, groups.groups, q)
                        : mesh_boundary(b, curves, opt.boundary_samples, q);
  };
  r.boundary_norm = q;
  r.boundary = boundary_of(bg);
  for (double l : r.boundary.curve_length) r.boundary_metric_length += l;
  r.metric_area = bg.metric_area();
  r.requested_points = r.metric_area + 0.5 * r.boundary_metric_length + 1;
  r.nfixed = static_cast<int>(r.boundary.points.size());
  const int requested_total = std::max(r.nfixed + 1, static_cast<int>(std::lround(r.requested_points)));
  const int interior_final = requested_total - r.nfixed;

  // Levels: the coarsest keeps at least opt.coarse_points interior points.
  int nlevels = 0;
  if (opt.multilevel)
    while (interior_final / std::pow(4.0, nlevels + 1) >= opt.coarse_points && nlevels < 12) ++nlevels;

  SplitMergeOptions smo = opt.split;
  smo.q = opt.p;
  MinimizeResult last;
  bool outer_converged = false, changed = false, count_stop = false;
  int cycle = 0;  // global cycle counter (history)
  auto on_iter = [&](const IterationRecord& it) {
    if (it.iteration > 0 && it.iteration % 25 == 0)
      say("  cycle " + std::to_string(it.cycle) + " iteration " + std::to_string(it.iteration) +
          ": E = " + fmt("%.6e", it.energy) + ", |grad E| = " + fmt("%.3e", it.grad_norm));
  };
  std::vector<Vec2> sites;
  int nfixed = 0;
  BoundaryPoints bnd;
  std::unique_ptr<Background> owned;
  const Background* lbg = &bg;
  LevelRecord* lrec = nullptr;

  auto minimise = [&](int cyc, bool polish) {
    last = minimize_energy(*lbg, sites, nfixed, opt.p, opt.lbfgs, &r.history, cyc, on_iter);
    r.energy_timers += last.timers;
    CycleRecord c;
    c.cycle = cyc;
    c.polish = polish;
    c.level = lrec->level;
    c.iterations = last.iterations;
    c.evaluations = last.evaluations;
    c.energy = last.energy;
    c.grad_norm = last.grad_norm;
    c.converged = last.converged;
    c.stop = last.stop;
    c.window_move = last.window_move;
    c.window_edge_change = last.window_edge_change;
    c.points = static_cast<int>(sites.size());
    r.iterations += last.iterations;
    r.evaluations += last.evaluations;
    lrec->iterations += last.iterations;
    lrec->evaluations += last.evaluations;
    return c;
  };
  // Free sites renumbered along a Hilbert curve (memory locality of the energy evaluation).
  auto sort_free = [&]() {
    std::vector<int> order = spatial_order(sites, nfixed);
    std::vector<Vec2> s(sites.begin(), sites.begin() + nfixed);
    for (int i : order) s.push_back(sites[i]);
    sites.swap(s);
  };

  for (int level = nlevels; level >= 0; --level) {
    const auto t0 = Clock::now();
    const double f = std::pow(0.5, level);
    if (level > 0) {
      owned = std::make_unique<Background>(bg.scaled(f));
      lbg = owned.get();
    } else {
      lbg = &bg;
    }
    r.levels.push_back(LevelRecord{});
    lrec = &r.levels.back();
    lrec->level = level;
    lrec->scale = f;
    bnd = level > 0 ? boundary_of(*lbg) : r.boundary;
    const std::vector<Vec2> prev_free(sites.begin() + std::min<size_t>(nfixed, sites.size()), sites.end());
    nfixed = static_cast<int>(bnd.points.size());
    sites = bnd.points;
    const int target_interior = static_cast<int>(std::lround(interior_final / std::pow(4.0, level)));
    if (level == nlevels) {
      int n0 = opt.initial_points;
      if (n0 < 0 || nlevels > 0) n0 = std::max(1, target_interior);
      std::vector<Vec2> seeds;
      if (opt.seed_mode == SeedMode::Lattice) {
        seeds = lattice_points(*lbg, sites, opt.lattice_delta, 4 * n0 + 100, opt.lattice_phase);
        lrec->start_points = static_cast<int>(seeds.size()) + nfixed;
        if (opt.start_jitter > 0) jitter_start(*lbg, seeds, opt.start_jitter, opt.seed);
        sites.insert(sites.end(), seeds.begin(), seeds.end());
        if (opt.exact_count && opt.initial_points < 0)
          adjust_count(*lbg, sites, nfixed, bnd.segments, nfixed + target_interior, smo);
        n0 = static_cast<int>(sites.size()) - nfixed;
      } else {
        seeds = seed_points(*lbg, n0, opt.seed_mode, opt.seed);
        sites.insert(sites.end(), seeds.begin(), seeds.end());
        lrec->start_points = static_cast<int>(sites.size());
      }
      r.initial_sites = sites;
      if (opt.start_only) return r;
      say(std::to_string(r.boundary.curve_length.size()) + " boundary curves, " + std::to_string(r.nfixed) +
          " boundary points; requested points " + fmt("%.1f", r.requested_points) + " (metric area " +
          fmt("%.1f", r.metric_area) + ")" +
          (nlevels ? "; " + std::to_string(nlevels + 1) + " levels, the coarsest with " + std::to_string(nfixed) +
                         " boundary points and " + std::to_string(n0) + " interior seeds"
                   : "; " + std::to_string(n0) + " interior seeds") +
          (opt.seed_mode == SeedMode::Lattice ? " (lattice: " + std::to_string(lrec->start_points - nfixed) + " grown)"
                                              : std::string()));
    } else {
      auto kids = refine_sites(*lbg, prev_free);
      sites.insert(sites.end(), kids.begin(), kids.end());
      lrec->start_points = static_cast<int>(sites.size());
      if (opt.exact_count) adjust_count(*lbg, sites, nfixed, bnd.segments, nfixed + target_interior, smo);
      say("level " + std::to_string(level) + ": " + std::to_string(nfixed) + " boundary points, " +
          std::to_string(kids.size()) + " children -> " + std::to_string(sites.size() - nfixed) + " interior points");
    }
    sort_free();
    int good = 0;
    outer_converged = false;
    changed = false;
    // The coarsest level (or a single level) needs two settled cycles in a row (thesis §4.5); a
    // finer level starts from a settled coarser one, and a lattice start is settled by
    // construction, so one settled cycle is enough there.
    const int need = level == nlevels && opt.seed_mode != SeedMode::Lattice ? 2 : 1;
    for (int k = 1; k <= opt.max_cycles; ++k) {
      ++cycle;
      double tol = opt.change_tol;
      if (k > opt.ramp_after) tol = std::min(opt.change_tol_max, opt.change_tol + 0.005 * (k - opt.ramp_after));
      CycleRecord c = minimise(cycle, false);
      c.split = split_merge(*lbg, sites, nfixed, bnd.segments, smo);
      c.points = static_cast<int>(sites.size());
      c.tolerance = tol;
      r.cycles.push_back(c);
      ++lrec->cycles;
      changed = c.split.splits + c.split.merges + c.split.removed_outside > 0;
      say((nlevels ? "level " + std::to_string(level) + " " : std::string()) + "cycle " + std::to_string(cycle) +
          ": " + std::to_string(c.iterations) + " iterations (" + std::to_string(c.evaluations) +
          " evaluations, " + c.stop + "), E = " + fmt("%.6e", c.energy) + ", |grad E| = " + fmt("%.3e", c.grad_norm) +
          "; " + std::to_string(c.split.edges) + " edges, " + std::to_string(c.split.splits) + " splits, " +
          std::to_string(c.split.merges) + " merges" +
          (c.split.removed_outside ? ", " + std::to_string(c.split.removed_outside) + " removed" : std::string()) +
          " (" + fmt("%.2f", 100 * c.split.change_fraction()) + "%), " + std::to_string(c.points) + " points");
      if (changed) sort_free();
      if (c.split.change_fraction() < tol)
        ++good;
      else
        good = 0;
      if (good >= need) {
        outer_converged = true;
        break;
      }
      // Split/merge fighting the count: on a frame graded faster than the requested count can
      // follow, every cycle splits the edges that cross the jumps and the minimisation pulls the
      // points back (PHiLiP's coarse bl15_fb_p2 frame at 241 points: 304 -> 4,543 points over
      // 30 cycles, 347 s). Beyond kCountGuard x the request (or below 1 / kCountGuard) the cycles
      // stop; the count is restored below. The loop's frames stay within 1.02x (89 runs of the
      // studies).
      const double ratio = static_cast<double>(sites.size()) / std::max(1, nfixed + target_interior);
      if (opt.exact_count && opt.initial_points < 0 && (ratio > kCountGuard || ratio < 1 / kCountGuard)) {
        count_stop = true;
        say("split/merge stopped: " + std::to_string(sites.size()) + " points, " + fmt("%.2f", ratio) +
            "x the request (the frame changes faster than the requested count can follow: graded, or its rows bent; "
            "see the frame's warnings)");
        break;
      }
    }
    // The count is set to the request at the finest level even when the last cycle settled:
    // split/merge may settle with the count far from it (a graded S-shock frame: 847 points
    // asked, three cycles of splits only, settled at 1311).
    if (level == 0 && opt.exact_count && opt.initial_points < 0) {
      const int d = adjust_count(*lbg, sites, nfixed, bnd.segments, requested_total, smo);
      if (d) {
        say("point count set to the requested " + std::to_string(requested_total) + " (" + (d > 0 ? "+" : "") +
            std::to_string(d) + ")");
        sort_free();
        changed = true;
      }
    }
    if (level == 0 && changed && opt.polish) {
      ++cycle;
      CycleRecord c = minimise(cycle, true);
      r.cycles.push_back(c);
      say("final minimisation: " + std::to_string(c.iterations) + " iterations (" + c.stop + "), E = " +
          fmt("%.6e", c.energy) + ", |grad E| = " + fmt("%.3e", c.grad_norm));
    }
    lrec->points = static_cast<int>(sites.size());
    lrec->boundary_points = nfixed;
    lrec->seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    if (nlevels)
      say("level " + std::to_string(level) + " done: " + std::to_string(lrec->points) + " points, " +
          std::to_string(lrec->cycles) + " cycles, " + std::to_string(lrec->iterations) + " iterations, " +
          fmt("%.2f", lrec->seconds) + " s");
  }
  int removed = remove_outside(bg, sites, r.nfixed);
  if (removed) say(std::to_string(removed) + " points outside the domain removed");
  r.sites = sites;
  r.energy = last.energy;
  r.grad_norm = last.grad_norm;
  r.converged = outer_converged && last.converged;
  if (r.converged)
    r.stop = "converged";
  else if (!outer_converged)
    r.stop = count_stop ? "split/merge stopped: the point count left [1/" + fmt("%g", kCountGuard) + ", " +
                              fmt("%g", kCountGuard) + "] x the request"
                        : "split/merge still changing more than the tolerance after " + std::to_string(opt.max_cycles) +
                              " cycles";
  else
    r.stop = "last minimisation stopped early: " + last.stop;
  r.mesh = triangulate_domain(sites, r.nfixed, r.boundary.segments, r.boundary.segment_group, groups);
  if (bg.metric_cells()) r.metric_flips = metric_flip_triangles(r.mesh, bg, &r.metric_flips_capped);
  if (!bg.is_analytic()) attach_frame(r.mesh, bg);
  say(std::to_string(r.sites.size()) + " points (requested " + fmt("%.0f", r.requested_points) + "), " +
      std::to_string(r.mesh.num_cells()) + " triangles; " + r.stop);
  return r;
}

double frame_metric_scale() { return kSplit * Frame::cell_metric_factor(); }

void attach_frame(Mesh& m, const Background& bg) {
  std::vector<Mat2> M(m.num_cells());
  int hint = -1;
  for (int c = 0; c < m.num_cells(); ++c) {
    int q = bg.locate(cell_centroid(m, c), hint);
    if (q < 0) q = bg.locate(m.nodes[m.cells[c].v[0]], hint);
    if (q < 0) q = 0;
    hint = q;
    M[c] = bg.cell(q).M / frame_metric_scale();
  }
  set_frame_field(m, M);
}

long metric_flip_triangles(Mesh& m, const Background& bg, bool* capped) {
  std::vector<std::array<int, 3>> tris(m.num_cells());
  for (int c = 0; c < m.num_cells(); ++c) tris[c] = {m.cells[c].v[0], m.cells[c].v[1], m.cells[c].v[2]};
  // the energy's neighbour graph rule, everywhere (also across metric jumps: Euclidean triangles
  // there, between points placed by metric cells, cost 4-60x in the loop's DG error on S-shock and
  // boundary-layer frames, measured); edges without a second triangle (the domain's boundary,
  // holes) are never flipped
  MetricGraph g = build_metric_graph(bg, m.nodes, std::move(tris));
  for (int c = 0; c < m.num_cells(); ++c) {
    m.cells[c].v = {g.tris[c][0], g.tris[c][1], g.tris[c][2], -1};
    m.cells[c].nv = 3;
  }
  if (capped) *capped = g.capped;
  return g.flips;
}

nlohmann::json to_json(const LpcvtResult& r) {
  using nlohmann::json;
  json j;
  j["points"] = r.sites.size();
  j["boundary_points"] = r.nfixed;
  j["requested_points"] = r.requested_points;
  j["points_ratio"] = r.requested_points > 0 ? r.sites.size() / r.requested_points : 0.0;
  j["metric_area"] = r.metric_area;
  j["boundary_metric_length"] = r.boundary_metric_length;
  j["boundary_norm"] = r.boundary_norm;
  j["triangles"] = r.mesh.num_cells();
  j["metric_flips"] = r.metric_flips;
  j["metric_flips_capped"] = r.metric_flips_capped;
  j["requested_triangles"] = 2 * r.metric_area;
  j["iterations"] = r.iterations;
  j["evaluations"] = r.evaluations;
  j["cycles"] = r.cycles.size();
  j["energy"] = r.energy;
  j["grad_norm"] = r.grad_norm;
  j["converged"] = r.converged;
  j["stop"] = r.stop;
  json cyc = json::array();
  for (const CycleRecord& c : r.cycles) {
    cyc.push_back({{"cycle", c.cycle}, {"polish", c.polish}, {"iterations", c.iterations},
                   {"evaluations", c.evaluations}, {"energy", c.energy}, {"grad_norm", c.grad_norm},
                   {"converged", c.converged}, {"stop", c.stop}, {"points", c.points},
                   {"window_move", c.window_move >= 0 ? json(c.window_move) : json(nullptr)},
                   {"window_edge_change", c.window_edge_change >= 0 ? json(c.window_edge_change) : json(nullptr)},
                   {"edges", c.split.edges}, {"splits", c.split.splits}, {"merges", c.split.merges},
                   {"removed", c.split.removed_outside}, {"change_fraction", c.split.change_fraction()},
                   {"tolerance", c.tolerance}, {"level", c.level}, {"edge_length_min", c.split.min_length},
                   {"edge_length_mean", c.split.mean_length}, {"edge_length_max", c.split.max_length}});
  }
  j["cycle_history"] = cyc;
  json lv = json::array();
  for (const LevelRecord& l : r.levels)
    lv.push_back({{"level", l.level}, {"scale", l.scale}, {"points", l.points}, {"boundary_points", l.boundary_points},
                  {"start_points", l.start_points}, {"cycles", l.cycles}, {"iterations", l.iterations},
                  {"evaluations", l.evaluations}, {"seconds", l.seconds}});
  j["levels"] = lv;
  json h = {{"cycle", json::array()}, {"iteration", json::array()}, {"energy", json::array()},
            {"grad_norm", json::array()}, {"step", json::array()}, {"points", json::array()},
            {"window_move", json::array()}, {"window_edge_change", json::array()}};
  for (const IterationRecord& it : r.history) {
    h["cycle"].push_back(it.cycle);
    h["iteration"].push_back(it.iteration);
    h["energy"].push_back(it.energy);
    h["grad_norm"].push_back(it.grad_norm);
    h["step"].push_back(it.step);
    h["points"].push_back(it.points);
    h["window_move"].push_back(it.window_move >= 0 ? json(it.window_move) : json(nullptr));
    h["window_edge_change"].push_back(it.window_edge_change >= 0 ? json(it.window_edge_change) : json(nullptr));
  }
  j["history"] = h;
  return j;
}

}  // namespace quadapt::lpcvt
