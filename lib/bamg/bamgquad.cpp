#include "bamg/bamgquad.hpp"

#include <algorithm>
#include <cmath>

#include "bamg/frame_metric.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "quad/mesh_utils.hpp"

namespace quadapt {

namespace {
// The mesh with only the nodes a cell or a boundary edge uses, renumbered in order. ffbamg
// aborts on a background vertex in no triangle ("Err mesh vertices N is not in a triangle",
// exit 2 with its crash dump), where every other tool accepts such a node.
Mesh without_unused_nodes(const Mesh& in) {
  std::vector<int> to(in.nodes.size(), -1);
  for (const Cell& c : in.cells)
    for (int k = 0; k < c.nv; ++k) to[c.v[k]] = 0;
  for (const BoundaryEdge& e : in.boundary) to[e.v[0]] = to[e.v[1]] = 0;
  Mesh out = in;
  out.nodes.clear();
  for (size_t v = 0; v < in.nodes.size(); ++v)
    if (to[v] == 0) {
      to[v] = static_cast<int>(out.nodes.size());
      out.nodes.push_back(in.nodes[v]);
    }
  for (Cell& c : out.cells)
    for (int k = 0; k < c.nv; ++k) c.v[k] = to[c.v[k]];
  for (BoundaryEdge& e : out.boundary) e.v = {to[e.v[0]], to[e.v[1]]};
  return out;
}
}  // namespace

Mesh bamg_quad(const Frame& fr, const BamgQuadOptions& opt, BamgQuadStats* stats, const std::string& path) {
  const Mesh frame = without_unused_nodes(fr.mesh);
  check_simple_boundary(frame, path);
  if (frame.cells.empty()) throw InputError(path, "the frame mesh has no cells");
  const std::vector<Eigen::Matrix2d> M = fr.oriented();
  BamgQuadStats st;
  st.frame_cells = frame.num_cells();
  st.target_complexity = fr.target_cells();
  if (!(st.target_complexity > 0) || !std::isfinite(st.target_complexity))
    throw InputError(path, "the frame's element count int |det M|/4 is not positive and finite");
  // About 4 cells per BAMG vertex (T ~ 2 V triangles, ~2 cells each): a frame that asks for more
  // than the vertex limit gives BAMG stops at the limit, far from the target, so refuse it here.
  if (opt.ffbamg.max_vertices > 0 && st.target_complexity > 4.0 * opt.ffbamg.max_vertices)
    throw InputError(path, "the frame asks for " + sci(st.target_complexity) + " cells; BAMG would need about " +
                               sci(st.target_complexity / 4) + " vertices, more than --max-vertices " +
                               std::to_string(opt.ffbamg.max_vertices) +
                               "; check the frame's size convention (--convention) or raise --max-vertices");
  st.edge_factor = opt.edge_factor > 0 ? opt.edge_factor : default_bamg_edge_factor();

  InriaMesh bg;
  try {
    bg = bamg_background(frame);
  } catch (const InputError& e) {
    throw InputError(path, std::string(e.what()).substr(7));  // strip "frame: "
  }
  const auto cell_metric = bamg_cell_metrics(M, st.edge_factor);
  const auto vmetric = vertex_metrics(frame, cell_metric, opt.log_euclidean);
  // Calibration on BAMG's triangle count: Blossom-Quad pairs the triangles and the split makes
  // 4 cells of a quad and 3 of a triangle, so T triangles give 2 T + (unpaired triangles) cells,
  // about 2 T; BAMG is rerun until the predicted count is within the tolerance, then Blossom runs
  // once. Only when Blossom's own count still misses (its clean-up loses a few per cent on small
  // irregular triangulations) and BAMG runs remain, the prediction takes the measured cells per
  // triangle and the path goes on.
  const int max_runs = std::max(1, opt.max_runs);
  double factor = 1, per_triangle = kCellsPerBamgTriangle;
  Mesh best;
  double best_err = 1e300;
  while (st.runs < max_runs) {
    FfbamgResult b;
    double b_err = 1e300, b_factor = factor, b_ratio = 0;
    while (st.runs < max_runs) {
      std::vector<Eigen::Matrix2d> scaled = vmetric;
      for (auto& m : scaled) m *= factor;
      FfbamgResult r;
      try {
        r = run_ffbamg(bg, scaled, opt.ffbamg);
      } catch (const FfbamgNotRunnable&) {
        throw;  // a missing ffbamg is not the frame's fault: not named with it
      } catch (const ExternalError& e) {
        throw ExternalError(path + ": " + e.what());  // the input named (docs/exit-codes.md)
      }
      const double ratio = per_triangle * static_cast<double>(r.mesh.triangles.size()) / st.target_complexity;
      if (st.runs == 0) st.first_ratio = ratio;
      ++st.runs;
      st.bamg_seconds += r.seconds;
      const double err = std::abs(ratio - 1);
      if (err < b_err) {
        b_err = err;
        b_factor = factor;
        b_ratio = ratio;
        b = std::move(r);
      }
      factor /= ratio;  // triangles ~ sqrt(det(factor * 𝓜)) = factor * ...
      if (err <= opt.calibration_tolerance) break;
    }
    Mesh tri = mesh_from_bamg(b.mesh, frame);
    RecombineStats rs;
    Mesh q = recombine_to_all_quads(tri, opt.recombine, &rs, path + " (BAMG triangles)");
    ++st.blossom_runs;
    const double ratio = q.num_cells() / st.target_complexity;
    const double err = std::abs(ratio - 1);
    if (err < best_err) {
      best_err = err;
      best = std::move(q);
      st.bamg_command = b.command;
      st.bamg_vertices = tri.num_nodes();
      st.bamg_triangles = tri.num_cells();
      st.recombine = rs;
      st.metric_factor = b_factor;
      st.predicted_ratio = b_ratio;
      st.cells = best.num_cells();
      st.complexity_ratio = ratio;
    }
    if (err <= opt.calibration_tolerance || tri.num_cells() == 0) break;
    per_triangle = static_cast<double>(st.cells) / st.bamg_triangles;  // measured
    factor = b_factor / ratio;
  }
  if (stats) *stats = st;
  return best;
}

}  // namespace quadapt
