#include "quality/mesh_quality.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "quality/measures.hpp"

namespace quadapt {

namespace {
/// Cells of a frame stretched at least this much have an orientation (frame.orientation_median_deg).
constexpr double kOrientedStretch = 1.01;
}  // namespace

ShapeStats shape_stats(const Mesh& m, const std::vector<Eigen::Matrix2d>& M) {
  ShapeStats s;
  double angle_sum = 0, sj_sum = 0, dev_sum = 0;
  long corners = 0, quad_corners = 0, near_right = 0;
  std::vector<double> ratios, orientations;
  s.angle_min_deg = INFINITY;
  s.angle_max_deg = -INFINITY;
  s.scaled_jacobian_min = INFINITY;
  Vec2 p[4];
  for (int c = 0; c < m.num_cells(); ++c) {
    CellShape cs;
    if (m.is_curved()) {
      cs = curved_cell_shape(m, c, M.empty() ? nullptr : &M[c]);
    } else {
      if (M.empty()) cell_points(m, c, p);
      else cell_points(m, c, M[c], p);
      cs = cell_shape(p, m.cells[c].nv);
    }
    for (int i = 0; i < cs.nv; ++i) {
      const double a = cs.angle_deg[i];
      s.angle_min_deg = std::min(s.angle_min_deg, a);
      s.angle_max_deg = std::max(s.angle_max_deg, a);
      angle_sum += a;
      ++corners;
      if (cs.nv == 4) {
        ++quad_corners;
        dev_sum += std::abs(a - 90.0);
        if (a >= 80.0 && a <= 100.0) ++near_right;
      }
    }
    s.scaled_jacobian_min = std::min(s.scaled_jacobian_min, cs.scaled_jacobian);
    sj_sum += cs.scaled_jacobian;
    if (cs.nv == 4) {
      ratios.push_back(cs.edge_ratio());
      orientations.push_back(cs.orientation_deg);
    }
  }
  if (corners == 0) return ShapeStats{};
  s.angle_mean_deg = angle_sum / corners;
  s.quad_angle_share_80_100 = quad_corners ? static_cast<double>(near_right) / quad_corners : 0.0;
  s.quad_angle_deviation_mean_deg = quad_corners ? dev_sum / quad_corners : 0.0;
  s.scaled_jacobian_mean = sj_sum / m.num_cells();
  s.edge_ratio_median = median(ratios);
  s.orientation_median_deg = axial_median_deg(orientations);
  return s;
}

void vertex_regularity(const Mesh& m, int& interior, int& irregular) {
  // undirected cell edges with their multiplicity: an edge used once is a free (boundary) edge
  std::vector<std::pair<int, int>> e;
  for (const Cell& c : m.cells)
    for (int k = 0; k < c.nv; ++k) {
      const int a = c.v[k], b = c.v[(k + 1) % c.nv];
      e.emplace_back(std::min(a, b), std::max(a, b));
    }
  std::sort(e.begin(), e.end());
  std::vector<int> valence(m.num_nodes(), 0);
  std::vector<char> on_boundary(m.num_nodes(), 0), used(m.num_nodes(), 0);
  for (size_t i = 0; i < e.size();) {
    size_t j = i;
    while (j < e.size() && e[j] == e[i]) ++j;
    ++valence[e[i].first];
    ++valence[e[i].second];
    used[e[i].first] = used[e[i].second] = 1;
    if (j - i == 1) on_boundary[e[i].first] = on_boundary[e[i].second] = 1;
    i = j;
  }
  interior = irregular = 0;
  for (int v = 0; v < m.num_nodes(); ++v) {
    if (!used[v] || on_boundary[v]) continue;
    ++interior;
    if (valence[v] != 4) ++irregular;
  }
}

QualityReport measure_quality(const Mesh& m, const Frame* fr, const std::string& frame_path) {
  QualityReport r;
  vertex_regularity(m, r.interior_vertices, r.irregular_interior);
  r.nodes = m.num_nodes();
  r.geometric_order = m.geometric_order();
  r.cells = m.num_cells();
  r.quads = m.num_quads();
  r.triangles = m.num_triangles();
  r.area = total_area(m);
  r.groups = m.groups;
  r.group_edges.assign(m.groups.size(), 0);
  for (const BoundaryEdge& e : m.boundary)
    if (e.group >= 0 && e.group < static_cast<int>(m.groups.size())) ++r.group_edges[e.group];
  r.physical = shape_stats(m);
  if (!fr) return r;

  r.has_frame = true;
  const std::vector<Eigen::Matrix2d> Mf = fr->oriented();  // mapped cells stay counter-clockwise
  FrameStats& f = r.frame;
  f.file = frame_path;
  f.cells = fr->num_cells();
  f.continuous_complexity = fr->target_cells();
  std::vector<double> stretch, axis, axis_all;
  for (int c = 0; c < fr->num_cells(); ++c) {
    Eigen::JacobiSVD<Eigen::Matrix2d> svd(Mf[c], Eigen::ComputeFullV);
    const Eigen::Vector2d sv = svd.singularValues();  // decreasing
    stretch.push_back(sv(0) / sv(1));
    const Eigen::Vector2d longest = svd.matrixV().col(1);  // smallest sigma of M = largest h
    double a = std::atan2(longest.y(), longest.x()) * 180 / M_PI;
    axis_all.push_back(std::fmod(a + 360.0, 180.0));
    // a nearly isotropic cell has no long axis (the SVD's pick does not turn with the frame):
    // it would move the median of a rotated frame (92.07 -> 4.34 deg under a 90 deg turn)
    if (stretch.back() >= kOrientedStretch) axis.push_back(axis_all.back());
  }
  f.stretch_median = median(stretch);
  f.orientation_median_deg = axial_median_deg(axis.empty() ? axis_all : axis);

  const std::vector<Eigen::Matrix2d> M = fr->at_cells(m, &f.cells_outside);
  r.metric = shape_stats(m, M);

  std::vector<double> lengths;
  double sum = 0;
  int in_range = 0;
  const double lo = 1 / std::sqrt(2.0), hi = std::sqrt(2.0);
  for (int c = 0; c < m.num_cells(); ++c) {
    const Cell& cell = m.cells[c];
    for (int i = 0; i < cell.nv; ++i) {
      const Vec2 e = m.nodes[cell.v[(i + 1) % cell.nv]] - m.nodes[cell.v[i]];
      const double l = m.is_curved() ? Frame::cell_metric_factor() * curved_edge_length(m, c, i, &M[c])
                                     : (Frame::cell_metric_factor() * M[c] * e).norm();
      lengths.push_back(l);
      sum += l;
      if (l >= lo && l <= hi) ++in_range;
    }
  }
  EdgeLengthStats& el = r.metric_edges;
  el.edges = static_cast<int>(lengths.size());
  if (!lengths.empty()) {
    el.min = *std::min_element(lengths.begin(), lengths.end());
    el.max = *std::max_element(lengths.begin(), lengths.end());
    el.mean = sum / lengths.size();
    el.median = median(lengths);
    el.share_in_range = static_cast<double>(in_range) / lengths.size();
  }
  return r;
}

namespace {
nlohmann::json shape_json(const ShapeStats& s) {
  return {{"angle_min_deg", s.angle_min_deg},
          {"angle_max_deg", s.angle_max_deg},
          {"angle_mean_deg", s.angle_mean_deg},
          {"quad_angle_share_80_100", s.quad_angle_share_80_100},
          {"quad_angle_deviation_mean_deg", s.quad_angle_deviation_mean_deg},
          {"scaled_jacobian_min", s.scaled_jacobian_min},
          {"scaled_jacobian_mean", s.scaled_jacobian_mean},
          {"edge_ratio_median", s.edge_ratio_median},
          {"orientation_median_deg", s.orientation_median_deg}};
}
}  // namespace

nlohmann::json to_json(const QualityReport& r) {
  nlohmann::json j;
  j["nodes"] = r.nodes;
  j["geometric_order"] = r.geometric_order;
  j["cells"] = r.cells;
  j["quads"] = r.quads;
  j["triangles"] = r.triangles;
  j["area"] = r.area;
  j["boundary"] = nlohmann::json::array();
  for (size_t g = 0; g < r.groups.size(); ++g)
    j["boundary"].push_back({{"name", r.groups[g].name}, {"tag", r.groups[g].tag}, {"edges", r.group_edges[g]}});
  j["interior_vertices"] = r.interior_vertices;
  j["irregular_interior_vertices"] = r.irregular_interior;
  j["irregular_interior_share"] = r.interior_vertices ? static_cast<double>(r.irregular_interior) / r.interior_vertices : 0.0;
  j["physical"] = shape_json(r.physical);
  if (r.has_frame) {
    nlohmann::json metric = shape_json(r.metric);
    metric["edge_length"] = {{"edges", r.metric_edges.edges},
                             {"min", r.metric_edges.min},
                             {"max", r.metric_edges.max},
                             {"mean", r.metric_edges.mean},
                             {"median", r.metric_edges.median},
                             {"share_in_range", r.metric_edges.share_in_range}};
    j["metric"] = metric;
    j["frame"] = {{"file", r.frame.file},
                  {"cells", r.frame.cells},
                  {"continuous_complexity", r.frame.continuous_complexity},
                  {"actual_cells", r.cells},
                  {"cells_over_continuous", r.frame.continuous_complexity > 0 ? r.cells / r.frame.continuous_complexity : 0.0},
                  {"stretch_median", r.frame.stretch_median},
                  {"orientation_median_deg", r.frame.orientation_median_deg},
                  {"cells_outside", r.frame.cells_outside}};
  }
  return j;
}

}  // namespace quadapt
