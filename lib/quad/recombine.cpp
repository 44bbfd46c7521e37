#include "quad/recombine.hpp"

#include "core/error.hpp"
#include "quad/mesh_utils.hpp"
#include "quad/subdivide.hpp"

namespace quadapt {

Mesh recombine_to_all_quads(const Mesh& tri_in, const RecombineOptions& opt, RecombineStats* stats,
                            const std::string& path) {
  require_triangulation(tri_in, path);
  RecombineStats st;
  st.triangles_in = tri_in.num_cells();
  Mesh tri = tri_in;
  tri.clear_fields();
  Mesh qd;
  if (opt.matching == RecombineOptions::Matching::Metric) {
    qd = metric_pairing(tri, opt.frame, opt.metric, &st.metric);
  } else {
    st.parity_split = make_triangle_count_even(tri);
    qd = blossom_recombine(tri, opt.blossom, &st.blossom);
  }
  Mesh out = opt.split ? split_to_all_quads(qd) : std::move(qd);
  st.quality = quality_summary(out);
  st.cells_out = out.num_cells();
  if (st.quality.inverted > 0)
    throw NumericalError(path + ": the all-quad mesh has " + std::to_string(st.quality.inverted) +
                         " inverted or degenerate cells");
  if (stats) *stats = st;
  return out;
}

}  // namespace quadapt
