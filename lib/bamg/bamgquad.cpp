#include "bamg/bamgquad.hpp"

#include <algorithm>
#include <cmath>

#include "bamg/frame_metric.hpp"
#include "core/error.hpp"

namespace quadapt {

Mesh bamg_quad(const Frame& fr, const BamgQuadOptions& opt, BamgQuadStats* stats, const std::string& path) {
  const Mesh& frame = fr.mesh;
  if (frame.cells.empty()) throw InputError(path, "the frame mesh has no cells");
  const std::vector<Eigen::Matrix2d> M = fr.oriented();
  BamgQuadStats st;
  st.frame_cells = frame.num_cells();
  st.target_complexity = fr.target_cells();
  if (!(st.target_complexity > 0) || !std::isfinite(st.target_complexity))
    throw InputError(path, "the frame's element count int |det M|/4 is not positive and finite");
  st.edge_factor = opt.edge_factor > 0 ? opt.edge_factor : default_bamg_edge_factor();

  InriaMesh bg;
  try {
    bg = bamg_background(frame);
  } catch (const InputError& e) {
    throw InputError(path, std::string(e.what()).substr(7));  // strip "frame: "
  }
  const auto cell_metric = bamg_cell_metrics(M, st.edge_factor);
  const auto vmetric = vertex_metrics(frame, cell_metric, opt.log_euclidean);
  // Calibration on BAMG's triangle count alone: Blossom-Quad pairs the triangles and the split
  // makes 4 cells of a quad and 3 of a triangle, so T triangles give 2 T + (unpaired triangles)
  // cells, about 2 T; BAMG is rerun until 2 T is within the tolerance, and Blossom runs once.
  const int max_runs = std::max(1, opt.max_runs);
  double factor = 1;
  FfbamgResult best;
  double best_err = 1e300;
  for (int run = 0; run < max_runs; ++run) {
    std::vector<Eigen::Matrix2d> scaled = vmetric;
    for (auto& m : scaled) m *= factor;
    FfbamgResult r = run_ffbamg(bg, scaled, opt.ffbamg);
    const double ratio = kCellsPerBamgTriangle * static_cast<double>(r.mesh.triangles.size()) / st.target_complexity;
    ++st.runs;
    st.bamg_seconds += r.seconds;
    if (run == 0) st.first_ratio = ratio;
    const double err = std::abs(ratio - 1);
    if (err < best_err) {
      best_err = err;
      st.metric_factor = factor;
      st.predicted_ratio = ratio;
      best = std::move(r);
    }
    if (err <= opt.calibration_tolerance) break;
    factor /= ratio;  // triangles ~ sqrt(det(factor * 𝓜)) = factor * ...
  }
  st.bamg_command = best.command;
  Mesh tri = mesh_from_bamg(best.mesh, frame);
  st.bamg_vertices = tri.num_nodes();
  st.bamg_triangles = tri.num_cells();
  Mesh q = recombine_to_all_quads(tri, opt.recombine, &st.recombine, path + " (BAMG triangles)");
  st.cells = q.num_cells();
  st.complexity_ratio = st.cells / st.target_complexity;
  if (stats) *stats = st;
  return q;
}

}  // namespace quadapt
