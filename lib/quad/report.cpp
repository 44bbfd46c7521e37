#include "quad/report.hpp"

namespace quadapt {

nlohmann::json to_json(const QualitySummary& q) {
  return {{"cells", q.cells},
          {"quads", q.quads},
          {"triangles", q.triangles},
          {"min_angle_deg", q.min_angle_deg},
          {"mean_angle_deg", q.mean_angle_deg},
          {"max_angle_deg", q.max_angle_deg},
          {"mean_cell_min_angle_deg", q.mean_cell_min_angle_deg},
          {"angles_below_30", q.angles_below_30},
          {"min_scaled_jacobian", q.min_scaled_jacobian},
          {"mean_scaled_jacobian", q.mean_scaled_jacobian},
          {"inverted", q.inverted},
          {"area", q.area}};
}

nlohmann::json to_json(const StretchSummary& s) {
  return {{"mean_stretch", s.mean_stretch},
          {"mean_angle_deg", s.mean_angle_deg},
          {"median_stretch", s.median_stretch},
          {"median_angle_deg", s.median_angle_deg}};
}

nlohmann::json to_json(const RecombineStats& s) {
  return {{"triangles_in", s.triangles_in},
          {"parity_split", s.parity_split},
          {"after_blossom",
           {{"triangles_in", s.blossom.triangles_in},
            {"quads", s.blossom.quads},
            {"triangles", s.blossom.triangles},
            {"gmsh_quads", s.blossom.gmsh_quads},
            {"rejected_pairs", s.blossom.rejected_pairs},
            {"greedy_pairs", s.blossom.greedy_pairs},
            {"reoriented", s.blossom.reoriented},
            {"fell_back", s.blossom.fell_back},
            {"fallback_reason", s.blossom.fallback_reason}}},
          {"after_metric_matching",
           {{"triangles_in", s.metric.triangles_in},
            {"quads", s.metric.quads},
            {"triangles", s.metric.triangles},
            {"wall_triangles", s.metric.wall_triangles},
            {"candidate_pairs", s.metric.candidate_pairs},
            {"mean_metric_quality", s.metric.mean_quality}}},
          {"flat_boundary_corners", {{"found", s.corners.flat_vertices}, {"split", s.corners.split}}},
          {"cells", s.cells_out},
          {"quality", to_json(s.quality)}};
}

}  // namespace quadapt
