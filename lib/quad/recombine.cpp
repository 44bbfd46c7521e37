#include "quad/recombine.hpp"

#include "core/error.hpp"
#include "mesh/label.hpp"
#include "mesh/validate.hpp"
#include "quad/mesh_utils.hpp"
#include "quad/subdivide.hpp"

namespace quadapt {

Mesh recombine_to_all_quads(const Mesh& tri_in, const RecombineOptions& opt, RecombineStats* stats,
                            const std::string& path) {
  require_triangulation(tri_in, path);
  // the metric matching needs the frame its header names (with none it paired in x-y and said
  // nothing: a library user's review, session 38; the recombine tool refused it already)
  if (opt.matching == RecombineOptions::Matching::Metric && opt.frame.empty())
    throw InputError(path, "the metric matching needs a frame: RecombineOptions::with_frame(one M per triangle)");
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
  // a boundary vertex in one quad on a smooth part of the boundary (a near-180-degree corner,
  // which the split keeps and which cannot even be curved): its quad goes back to two triangles
  st.corners = split_flat_boundary_corners(qd);
  Mesh out = opt.split ? split_to_all_quads(qd) : std::move(qd);
  st.quality = quality_summary(out);
  st.cells_out = out.num_cells();
  // never a mesh that the tools reading it refuse (validate_mesh's test of each cell)
  int bad = 0, first_bad = -1;
  std::string first_problem;
  for (int c = 0; c < out.num_cells(); ++c)
    if (std::string problem = cell_shape_problem(out, c); !problem.empty() && bad++ == 0) {
      first_bad = c;
      first_problem = std::move(problem);
    }
  if (bad > 0)
    throw NumericalError(path + ": the all-quad mesh has " + std::to_string(bad) + " inverted or degenerate cells (" +
                         cell_label(out, first_bad) + " is " + first_problem + ")");
  if (stats) *stats = st;
  return out;
}

}  // namespace quadapt
