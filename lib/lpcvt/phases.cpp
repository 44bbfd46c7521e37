#include "lpcvt/phases.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>

#include "core/error.hpp"
#include "core/format.hpp"
#include "frame/frame.hpp"
#include "mesh/triangulation.hpp"
#include "quad/recombine.hpp"
#include "quality/mesh_quality.hpp"

namespace quadapt::lpcvt {

Vec2 phase_offset(int k, int K) {
  if (K <= 1) return Vec2::Zero();
  // generator a: the integer nearest K / golden ratio, made coprime with K (then k a mod K runs
  // over every residue, so each axis alone gets K distinct phases)
  auto gcd = [](int x, int y) {
    while (y) {
      const int t = x % y;
      x = y;
      y = t;
    }
    return x;
  };
  int a = std::max(1, static_cast<int>(std::lround(K * 0.6180339887498949)));
  while (gcd(a, K) != 1) ++a;
  return Vec2(static_cast<double>(k % K) / K, static_cast<double>((static_cast<long>(k) * a) % K) / K);
}

bool PhaseScore::better_than(const PhaseScore& o) const {
  if (irregular != o.irregular) return irregular < o.irregular;
  return quality > o.quality + 1e-12;
}

PhaseScore recombine_score(const Mesh& tri) {
  RecombineOptions opt;
  opt.matching = RecombineOptions::Matching::Metric;
  opt.frame = frame_from_mesh(tri, "lpcvt output").oriented();
  RecombineStats st;
  const Mesh q = recombine_to_all_quads(tri, opt, &st, "lpcvt output");
  PhaseScore s;
  vertex_regularity(q, s.interior, s.irregular);
  s.unmatched = st.metric.triangles;
  s.quality = st.metric.mean_quality;
  return s;
}

PhaseRuns run_phases(const Background& bg, const LpcvtOptions& opt, int n,
                     const std::function<void(const std::string&)>& log) {
  // the starts first (cheap): a phase whose start equals an earlier one's is the same run
  std::vector<std::vector<Vec2>> starts;
  std::vector<int> todo;  // phases to run
  PhaseRuns out;
  out.runs = nlohmann::json::array();
  for (int k = 0; k < n; ++k) {
    LpcvtOptions o = opt;
    o.lattice_phase = phase_offset(k, n);
    o.start_only = true;
    std::vector<Vec2> start = run_lpcvt(bg, o, {}).initial_sites;
    if (std::find(starts.begin(), starts.end(), start) != starts.end()) continue;
    starts.push_back(std::move(start));
    todo.push_back(k);
  }
  struct Run {
    LpcvtResult r;
    PhaseScore score;
    double seconds = 0;
    std::exception_ptr error;
  };
  std::vector<Run> runs(todo.size());
  const int nt = std::max(1, std::min<int>(omp_get_max_threads(), static_cast<int>(todo.size())));
#pragma omp parallel for num_threads(nt) schedule(dynamic, 1) if (nt > 1)
  for (int i = 0; i < static_cast<int>(todo.size()); ++i) {
    if (nt > 1) omp_set_num_threads(1);  // this phase's own parallel regions: one thread
    Run& run = runs[i];
    try {
      LpcvtOptions o = opt;
      o.lattice_phase = phase_offset(todo[i], n);
      const auto t0 = std::chrono::steady_clock::now();
      run.r = run_lpcvt(bg, o, {});
      const TriangulationCheck ck = check_triangulation(run.r.mesh);
      if (!ck.ok())
        throw NumericalError("invalid output triangulation (phase " + std::to_string(todo[i]) + "): " + ck.summary());
      run.score = recombine_score(run.r.mesh);
      run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    } catch (...) {
      run.error = std::current_exception();
    }
  }
  for (const Run& run : runs)
    if (run.error) std::rethrow_exception(run.error);
  // report and choice in phase order
  int best = -1;
  for (int k = 0, i = 0; k < n; ++k) {
    const Vec2 off = phase_offset(k, n);
    nlohmann::json e = {{"phase", {off.x(), off.y()}}};
    if (i >= static_cast<int>(todo.size()) || todo[i] != k) {
      e["same_start_as_earlier"] = true;
      out.runs.push_back(e);
      continue;
    }
    const Run& run = runs[i];
    const PhaseScore& sc = run.score;
    e["irregular"] = sc.irregular;
    e["interior"] = sc.interior;
    e["unmatched_triangles"] = sc.unmatched;
    e["pair_quality"] = sc.quality;
    e["evaluations"] = run.r.evaluations;
    e["seconds"] = run.seconds;
    out.runs.push_back(e);
    if (log)
      log("phase " + std::to_string(k) + " (" + sci(off.x()) + ", " + sci(off.y()) + "): " +
          std::to_string(run.r.evaluations) + " evaluations, " + std::to_string(sc.irregular) + " of " +
          std::to_string(sc.interior) + " interior vertices irregular after recombine, pair quality " + sci(sc.quality));
    if (best < 0 || sc.better_than(runs[best].score)) {
      best = i;
      out.kept = k;
    }
    ++i;
  }
  out.best = std::move(runs[best].r);
  if (log) log("kept phase " + std::to_string(out.kept));
  return out;
}

}  // namespace quadapt::lpcvt
