#include "quad/quality_summary.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "quality/measures.hpp"

namespace quadapt {

namespace {
constexpr double kPi = 3.14159265358979323846;

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

CellShape shape_of(const Mesh& m, int c) {
  Vec2 p[4];
  cell_points(m, c, p);
  return cell_shape(p, m.cells[c].nv);
}

// Long-axis angle (degrees, [0,180)) and stretch of an SPD 2x2 tensor.
void axis_of(const Eigen::Matrix2d& J, double& stretch, double& angle_deg) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(J);
  double l0 = std::max(es.eigenvalues()(0), 1e-300), l1 = std::max(es.eigenvalues()(1), 1e-300);
  stretch = std::sqrt(l1 / l0);
  Eigen::Vector2d u = es.eigenvectors().col(1);
  double a = std::atan2(u.y(), u.x()) * 180 / kPi;
  angle_deg = std::fmod(a + 360.0, 180.0);
}
}  // namespace

double corner_angle_deg(const Mesh& m, int c, int i) { return shape_of(m, c).angle_deg[i]; }

double cell_min_angle_deg(const Mesh& m, int c) {
  const CellShape s = shape_of(m, c);
  return *std::min_element(s.angle_deg, s.angle_deg + s.nv);
}

double cell_max_angle_deg(const Mesh& m, int c) {
  const CellShape s = shape_of(m, c);
  return *std::max_element(s.angle_deg, s.angle_deg + s.nv);
}

double cell_scaled_jacobian(const Mesh& m, int c) { return shape_of(m, c).scaled_jacobian; }

Eigen::Matrix2d cell_shape_tensor(const Mesh& m, int c) {
  // Polygon moments relative to the first vertex (to limit cancellation).
  const Cell& cell = m.cells[c];
  const int n = cell.nv;
  const Vec2 o = m.nodes[cell.v[0]];
  double A = 0, cx = 0, cy = 0, ixx = 0, iyy = 0, ixy = 0;
  for (int i = 0; i < n; ++i) {
    Vec2 p = m.nodes[cell.v[i]] - o, q = m.nodes[cell.v[(i + 1) % n]] - o;
    double w = cross2(p, q);
    A += w;
    cx += (p.x() + q.x()) * w;
    cy += (p.y() + q.y()) * w;
    ixx += (p.x() * p.x() + p.x() * q.x() + q.x() * q.x()) * w;
    iyy += (p.y() * p.y() + p.y() * q.y() + q.y() * q.y()) * w;
    ixy += (p.x() * q.y() + 2 * p.x() * p.y() + 2 * q.x() * q.y() + q.x() * p.y()) * w;
  }
  A *= 0.5;
  Eigen::Matrix2d J = Eigen::Matrix2d::Zero();
  if (A == 0) return J;
  cx /= 6 * A;
  cy /= 6 * A;
  ixx /= 12;
  iyy /= 12;
  ixy /= 24;
  J(0, 0) = ixx / A - cx * cx;
  J(1, 1) = iyy / A - cy * cy;
  J(0, 1) = J(1, 0) = ixy / A - cx * cy;
  return J;
}

QualitySummary quality_summary(const Mesh& m) {
  QualitySummary s;
  s.cells = m.num_cells();
  s.quads = m.num_quads();
  s.triangles = m.num_triangles();
  if (s.cells == 0) return s;
  s.min_angle_deg = 1e300;
  s.min_scaled_jacobian = 1e300;
  double sum_angle = 0, sum_cellmin = 0, sum_sj = 0;
  long corners = 0;
  for (int c = 0; c < s.cells; ++c) {
    const CellShape sh = shape_of(m, c);
    double cmin = 1e300;
    for (int i = 0; i < sh.nv; ++i) {
      double a = sh.angle_deg[i];
      s.min_angle_deg = std::min(s.min_angle_deg, a);
      s.max_angle_deg = std::max(s.max_angle_deg, a);
      cmin = std::min(cmin, a);
      sum_angle += a;
      ++corners;
      if (a < 30) ++s.angles_below_30;
    }
    sum_cellmin += cmin;
    double sj = sh.scaled_jacobian;
    s.min_scaled_jacobian = std::min(s.min_scaled_jacobian, sj);
    sum_sj += sj;
    if (sj <= 0) ++s.inverted;
    s.area += cell_area(m, c);
  }
  s.mean_angle_deg = sum_angle / corners;
  s.mean_cell_min_angle_deg = sum_cellmin / s.cells;
  s.mean_scaled_jacobian = sum_sj / s.cells;
  return s;
}

StretchSummary stretch_summary(const Mesh& m, const std::vector<int>& cells_in) {
  std::vector<int> cells = cells_in;
  if (cells.empty())
    for (int c = 0; c < m.num_cells(); ++c) cells.push_back(c);
  StretchSummary s;
  if (cells.empty()) return s;
  Eigen::Matrix2d L = Eigen::Matrix2d::Zero();
  std::vector<double> st, ang;
  int used = 0;
  for (int c : cells) {
    Eigen::Matrix2d J = cell_shape_tensor(m, c);
    double d = J.determinant();
    if (!(d > 0)) continue;
    J /= std::sqrt(d);
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(J);
    Eigen::Vector2d lg = es.eigenvalues().array().log();
    L += es.eigenvectors() * lg.asDiagonal() * es.eigenvectors().transpose();
    ++used;
    double stretch, a;
    axis_of(J, stretch, a);
    st.push_back(stretch);
    ang.push_back(a);
  }
  if (used == 0) return s;
  L /= used;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(L);
  Eigen::Vector2d ex = es.eigenvalues().array().exp();
  Eigen::Matrix2d T = es.eigenvectors() * ex.asDiagonal() * es.eigenvectors().transpose();
  axis_of(T, s.mean_stretch, s.mean_angle_deg);
  s.median_stretch = median(st);
  s.median_angle_deg = axial_median_deg(ang);
  return s;
}

}  // namespace quadapt
