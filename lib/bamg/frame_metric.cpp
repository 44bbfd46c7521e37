#include "bamg/frame_metric.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <Eigen/LU>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include "core/error.hpp"
#include "mesh/mesh.hpp"
#include "quad/mesh_utils.hpp"

namespace quadapt {

namespace {
Eigen::Matrix2d spd_log(const Eigen::Matrix2d& A) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(0.5 * (A + A.transpose()));
  Eigen::Vector2d l = es.eigenvalues().array().max(1e-300).log();
  return es.eigenvectors() * l.asDiagonal() * es.eigenvectors().transpose();
}
Eigen::Matrix2d sym_exp(const Eigen::Matrix2d& L) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(0.5 * (L + L.transpose()));
  Eigen::Vector2d l = es.eigenvalues().array().exp();
  return es.eigenvectors() * l.asDiagonal() * es.eigenvectors().transpose();
}
double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }
std::uint64_t ukey(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}
}  // namespace

double default_bamg_edge_factor() { return std::sqrt(32.0 / std::sqrt(3.0)); }

std::vector<Eigen::Matrix2d> bamg_cell_metrics(const std::vector<Eigen::Matrix2d>& M, double edge_factor) {
  std::vector<Eigen::Matrix2d> out(M.size());
  const double s = 1.0 / (edge_factor * edge_factor);
  for (size_t c = 0; c < M.size(); ++c) out[c] = s * (M[c].transpose() * M[c]);
  return out;
}

std::vector<Eigen::Matrix2d> vertex_metrics(const Mesh& frame, const std::vector<Eigen::Matrix2d>& cell_metric,
                                            bool log_euclidean) {
  const int nn = frame.num_nodes();
  std::vector<Eigen::Matrix2d> acc(nn, Eigen::Matrix2d::Zero());
  std::vector<double> w(nn, 0.0);
  for (int c = 0; c < frame.num_cells(); ++c) {
    const double a = std::abs(cell_area(frame, c));
    const Eigen::Matrix2d X = log_euclidean ? spd_log(cell_metric[c]) : cell_metric[c];
    for (int k = 0; k < frame.cells[c].nv; ++k) {
      acc[frame.cells[c].v[k]] += a * X;
      w[frame.cells[c].v[k]] += a;
    }
  }
  for (int v = 0; v < nn; ++v) {
    if (w[v] <= 0) {
      acc[v] = Eigen::Matrix2d::Identity();  // unused node: BAMG ignores it
      continue;
    }
    acc[v] /= w[v];
    if (log_euclidean) acc[v] = sym_exp(acc[v]);
  }
  return acc;
}

InriaMesh bamg_background(const Mesh& frame) {
  InriaMesh b;
  b.vertices = frame.nodes;
  b.vertex_ref.assign(frame.nodes.size(), 0);
  for (int c = 0; c < frame.num_cells(); ++c) {
    const Cell& cell = frame.cells[c];
    const bool ccw = cell_area(frame, c) > 0;
    auto tri = [&](int a, int bb, int cc) {
      if (ccw) b.triangles.push_back({a, bb, cc, 0});
      else b.triangles.push_back({a, cc, bb, 0});
    };
    if (cell.nv == 3) {
      tri(cell.v[0], cell.v[1], cell.v[2]);
      continue;
    }
    const Vec2 *p[4];
    for (int k = 0; k < 4; ++k) p[k] = &frame.nodes[cell.v[k]];
    const double s = ccw ? 1.0 : -1.0;
    const bool d02_ok = s * cross2(*p[1] - *p[0], *p[2] - *p[0]) > 0 && s * cross2(*p[2] - *p[0], *p[3] - *p[0]) > 0;
    const bool d13_ok = s * cross2(*p[1] - *p[0], *p[3] - *p[0]) > 0 && s * cross2(*p[2] - *p[1], *p[3] - *p[1]) > 0;
    const bool shorter02 = (*p[2] - *p[0]).squaredNorm() <= (*p[3] - *p[1]).squaredNorm();
    if ((d02_ok && (shorter02 || !d13_ok)) || (!d02_ok && !d13_ok)) {
      tri(cell.v[0], cell.v[1], cell.v[2]);
      tri(cell.v[0], cell.v[2], cell.v[3]);
    } else {
      tri(cell.v[0], cell.v[1], cell.v[3]);
      tri(cell.v[1], cell.v[2], cell.v[3]);
    }
  }
  // Boundary: every free edge must be a listed boundary edge (conforming frame).
  std::unordered_map<std::uint64_t, int> group_of;
  for (const auto& e : frame.boundary) group_of[ukey(e.v[0], e.v[1])] = e.group;
  std::vector<std::array<int, 2>> fe;
  {
    Mesh oriented = frame;
    orient_counter_clockwise(oriented);
    fe = free_edges(oriented);
  }
  std::unordered_map<int, int> in_edge, out_edge;  // node -> index into fe
  for (size_t i = 0; i < fe.size(); ++i) {
    auto it = group_of.find(ukey(fe[i][0], fe[i][1]));
    if (it == group_of.end())
      throw InputError("frame: the boundary edge between (" + std::to_string(frame.nodes[fe[i][0]].x()) + ", " +
                       std::to_string(frame.nodes[fe[i][0]].y()) + ") and (" + std::to_string(frame.nodes[fe[i][1]].x()) +
                       ", " + std::to_string(frame.nodes[fe[i][1]].y()) +
                       ") belongs to no boundary group (non-conforming background meshes are not supported)");
    b.edges.push_back({fe[i][0], fe[i][1], it->second + 1});
    out_edge[fe[i][0]] = int(i);
    in_edge[fe[i][1]] = int(i);
  }
  const double turn_limit = 30.0 * M_PI / 180.0;
  for (const auto& [v, io] : out_edge) {
    auto ii = in_edge.find(v);
    if (ii == in_edge.end()) continue;
    const auto& ein = b.edges[ii->second];
    const auto& eout = b.edges[io];
    const Vec2 din = frame.nodes[fe[ii->second][1]] - frame.nodes[fe[ii->second][0]];
    const Vec2 dout = frame.nodes[fe[io][1]] - frame.nodes[fe[io][0]];
    const double turn = std::abs(std::atan2(cross2(din, dout), din.dot(dout)));
    if (ein[2] != eout[2] || turn > turn_limit) b.corners.push_back(v);
  }
  std::sort(b.corners.begin(), b.corners.end());
  b.required_vertices = b.corners;
  for (int v : b.corners) b.vertex_ref[v] = 1;
  return b;
}

Mesh mesh_from_bamg(const InriaMesh& bm, const Mesh& reference) {
  Mesh m;
  m.groups = reference.groups;
  m.domain_name = reference.domain_name;
  m.domain_tag = reference.domain_tag;
  m.nodes = bm.vertices;
  // Only vertices used by triangles are kept.
  std::vector<int> used(bm.vertices.size(), -1);
  int n = 0;
  for (const auto& t : bm.triangles)
    for (int k = 0; k < 3; ++k)
      if (used[t[k]] < 0) used[t[k]] = n++;
  m.nodes.assign(n, Vec2::Zero());
  for (size_t v = 0; v < bm.vertices.size(); ++v)
    if (used[v] >= 0) m.nodes[used[v]] = bm.vertices[v];
  for (const auto& t : bm.triangles) {
    Cell c;
    c.nv = 3;
    c.v = {used[t[0]], used[t[1]], used[t[2]], -1};
    m.cells.push_back(c);
  }
  orient_counter_clockwise(m);
  // Boundary groups by geometric matching to the reference boundary.
  auto fe = free_edges(m);
  for (const auto& e : fe) {
    const Vec2 mid = 0.5 * (m.nodes[e[0]] + m.nodes[e[1]]);
    double best = 1e300;
    int g = -1;
    for (const auto& r : reference.boundary) {
      double d = segment_distance(mid, reference.nodes[r.v[0]], reference.nodes[r.v[1]]);
      if (d < best) best = d, g = r.group;
    }
    if (g < 0) throw InputError("frame: no boundary groups to assign to the new boundary");
    m.boundary.push_back({{e[0], e[1]}, g});
  }
  return m;
}

}  // namespace quadapt
