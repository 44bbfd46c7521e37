#include "bamg/bamgquad.hpp"

#include <cmath>

#include "bamg/frame_metric.hpp"
#include "core/error.hpp"
#include "quality/mesh_quality.hpp"

namespace quadapt {

Mesh bamg_quad(const Mesh& frame, const BamgQuadOptions& opt, BamgQuadStats* stats, const std::string& path) {
  if (frame.cells.empty()) throw InputError(path, "the frame mesh has no cells");
  const std::vector<Eigen::Matrix2d> M = frame_matrices(frame, path);
  BamgQuadStats st;
  st.frame_cells = frame.num_cells();
  st.target_complexity = frame_complexity(frame, M);
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
  FfbamgResult fr = run_ffbamg(bg, vmetric, opt.ffbamg);
  st.bamg_seconds = fr.seconds;
  st.bamg_command = fr.command;
  Mesh tri = mesh_from_bamg(fr.mesh, frame);
  st.bamg_vertices = tri.num_nodes();
  st.bamg_triangles = tri.num_cells();
  Mesh q = recombine_to_all_quads(tri, opt.recombine, &st.recombine, path + " (BAMG triangles)");
  st.cells = q.num_cells();
  st.complexity_ratio = st.cells / st.target_complexity;
  if (stats) *stats = st;
  return q;
}

}  // namespace quadapt
