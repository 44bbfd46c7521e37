#include "lpcvt/lpcvt.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "lpcvt/triangulate.hpp"

namespace quadapt::lpcvt {

namespace {
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
  LpcvtResult r;
  // Boundary (§4.2).
  auto curves = boundary_curves(bg, opt.corner_angle);
  r.boundary = mesh_boundary(bg, curves, opt.boundary_samples);
  for (double l : r.boundary.curve_length) r.boundary_metric_length += l;
  r.metric_area = bg.metric_area();
  r.requested_points = r.metric_area + 0.5 * r.boundary_metric_length + 1;
  r.nfixed = static_cast<int>(r.boundary.points.size());
  // Interior seeds.
  int n0 = opt.initial_points;
  if (n0 < 0) n0 = std::max(1, static_cast<int>(std::lround(r.requested_points)) - r.nfixed);
  std::vector<Vec2> sites = r.boundary.points;
  auto seeds = seed_points(bg, n0, opt.seed_mode, opt.seed);
  sites.insert(sites.end(), seeds.begin(), seeds.end());
  r.initial_sites = sites;
  say(std::to_string(curves.size()) + " boundary curves, " + std::to_string(r.nfixed) +
      " boundary points; " + std::to_string(n0) + " interior seeds; requested points " +
      fmt("%.1f", r.requested_points) + " (metric area " + fmt("%.1f", r.metric_area) + ")");

  SplitMergeOptions smo = opt.split;
  smo.q = opt.p;
  int good = 0;
  bool outer_converged = false, changed = false;
  MinimizeResult last;
  auto on_iter = [&](const IterationRecord& it) {
    if (it.iteration > 0 && it.iteration % 25 == 0)
      say("  cycle " + std::to_string(it.cycle) + " iteration " + std::to_string(it.iteration) +
          ": E = " + fmt("%.6e", it.energy) + ", |grad E| = " + fmt("%.3e", it.grad_norm));
  };
  auto minimise = [&](int cycle, bool polish) {
    last = minimize_energy(bg, sites, r.nfixed, opt.p, opt.lbfgs, &r.history, cycle, on_iter);
    CycleRecord c;
    c.cycle = cycle;
    c.polish = polish;
    c.iterations = last.iterations;
    c.evaluations = last.evaluations;
    c.energy = last.energy;
    c.grad_norm = last.grad_norm;
    c.converged = last.converged;
    c.stop = last.stop;
    c.points = static_cast<int>(sites.size());
    r.iterations += last.iterations;
    r.evaluations += last.evaluations;
    return c;
  };
  int cycle = 0;
  for (cycle = 1; cycle <= opt.max_cycles; ++cycle) {
    double tol = opt.change_tol;
    if (cycle > opt.ramp_after) tol = std::min(opt.change_tol_max, opt.change_tol + 0.005 * (cycle - opt.ramp_after));
    CycleRecord c = minimise(cycle, false);
    c.split = split_merge(bg, sites, r.nfixed, r.boundary.segments, smo);
    c.points = static_cast<int>(sites.size());
    c.tolerance = tol;
    r.cycles.push_back(c);
    changed = c.split.splits + c.split.merges + c.split.removed_outside > 0;
    say("cycle " + std::to_string(cycle) + ": " + std::to_string(c.iterations) + " iterations (" +
        std::to_string(c.evaluations) + " evaluations, " + c.stop + "), E = " + fmt("%.6e", c.energy) +
        ", |grad E| = " + fmt("%.3e", c.grad_norm) + "; " + std::to_string(c.split.edges) + " edges, " +
        std::to_string(c.split.splits) + " splits, " + std::to_string(c.split.merges) + " merges" +
        (c.split.removed_outside ? ", " + std::to_string(c.split.removed_outside) + " removed" : std::string()) +
        " (" + fmt("%.2f", 100 * c.split.change_fraction()) + "%), " + std::to_string(c.points) + " points");
    if (c.split.change_fraction() < tol)
      ++good;
    else
      good = 0;
    if (good >= 2) {
      outer_converged = true;
      break;
    }
  }
  if (changed && opt.polish) {
    CycleRecord c = minimise(std::min(cycle, opt.max_cycles) + 1, true);
    r.cycles.push_back(c);
    say("final minimisation: " + std::to_string(c.iterations) + " iterations (" + c.stop + "), E = " +
        fmt("%.6e", c.energy) + ", |grad E| = " + fmt("%.3e", c.grad_norm));
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
    r.stop = "split/merge still changing more than the tolerance after " + std::to_string(opt.max_cycles) + " cycles";
  else
    r.stop = "last minimisation stopped early: " + last.stop;
  r.mesh = triangulate_domain(sites, r.nfixed, r.boundary.segments, r.boundary.segment_group, bg.mesh());
  say(std::to_string(r.sites.size()) + " points (requested " + fmt("%.0f", r.requested_points) + "), " +
      std::to_string(r.mesh.num_cells()) + " triangles; " + r.stop);
  return r;
}

nlohmann::json report_json(const LpcvtResult& r) {
  using nlohmann::json;
  json j;
  j["points"] = r.sites.size();
  j["boundary_points"] = r.nfixed;
  j["requested_points"] = r.requested_points;
  j["points_ratio"] = r.requested_points > 0 ? r.sites.size() / r.requested_points : 0.0;
  j["metric_area"] = r.metric_area;
  j["boundary_metric_length"] = r.boundary_metric_length;
  j["triangles"] = r.mesh.num_cells();
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
                   {"edges", c.split.edges}, {"splits", c.split.splits}, {"merges", c.split.merges},
                   {"removed", c.split.removed_outside}, {"change_fraction", c.split.change_fraction()},
                   {"tolerance", c.tolerance}, {"edge_length_min", c.split.min_length},
                   {"edge_length_mean", c.split.mean_length}, {"edge_length_max", c.split.max_length}});
  }
  j["cycle_history"] = cyc;
  json h = {{"cycle", json::array()}, {"iteration", json::array()}, {"energy", json::array()},
            {"grad_norm", json::array()}, {"step", json::array()}, {"points", json::array()}};
  for (const IterationRecord& it : r.history) {
    h["cycle"].push_back(it.cycle);
    h["iteration"].push_back(it.iteration);
    h["energy"].push_back(it.energy);
    h["grad_norm"].push_back(it.grad_norm);
    h["step"].push_back(it.step);
    h["points"].push_back(it.points);
  }
  j["history"] = h;
  return j;
}

}  // namespace quadapt::lpcvt
