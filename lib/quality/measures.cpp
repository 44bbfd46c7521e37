#include "quality/measures.hpp"

#include <algorithm>
#include <cmath>

namespace quadapt {

namespace {
double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }
double wrap180(double a) {
  a = std::fmod(a, 180.0);
  return a < 0 ? a + 180.0 : a;
}
}  // namespace

CellShape cell_shape(const Vec2* p, int nv) {
  CellShape s;
  s.nv = nv;
  s.scaled_jacobian = INFINITY;
  s.edge_min = INFINITY;
  s.edge_max = 0;
  for (int i = 0; i < nv; ++i) {
    const Vec2 en = p[(i + 1) % nv] - p[i];
    const Vec2 ep = p[(i + nv - 1) % nv] - p[i];
    double a = std::atan2(cross(en, ep), en.dot(ep)) * 180.0 / M_PI;
    if (a < 0) a += 360.0;
    s.angle_deg[i] = a;
    const double ln = en.norm(), lp = ep.norm();
    double sj = (ln > 0 && lp > 0) ? cross(en, ep) / (ln * lp) : 0.0;
    if (nv == 3) sj = std::clamp(sj * 2.0 / std::sqrt(3.0), -1.0, 1.0);
    s.scaled_jacobian = std::min(s.scaled_jacobian, sj);
    if (ln < s.edge_min) s.edge_min = ln;
    if (ln > s.edge_max) {
      s.edge_max = ln;
      s.orientation_deg = wrap180(std::atan2(en.y(), en.x()) * 180.0 / M_PI);
    }
  }
  return s;
}

void cell_points(const Mesh& m, int c, Vec2 out[4]) {
  const Cell& cell = m.cells[c];
  for (int i = 0; i < cell.nv; ++i) out[i] = m.nodes[cell.v[i]];
}

void cell_points(const Mesh& m, int c, const Eigen::Matrix2d& M, Vec2 out[4]) {
  const Cell& cell = m.cells[c];
  for (int i = 0; i < cell.nv; ++i) out[i] = M * m.nodes[cell.v[i]];
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  const size_t k = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + k, v.end());
  const double hi = v[k];
  if (v.size() % 2 == 1) return hi;
  return 0.5 * (*std::max_element(v.begin(), v.begin() + k) + hi);
}

double axial_median_deg(const std::vector<double>& angles_deg) {
  if (angles_deg.empty()) return 0;
  double sx = 0, sy = 0;
  for (double a : angles_deg) {
    sx += std::cos(2 * a * M_PI / 180);
    sy += std::sin(2 * a * M_PI / 180);
  }
  const double mean = 0.5 * std::atan2(sy, sx) * 180 / M_PI;  // in (-90, 90]
  std::vector<double> unwrapped;
  unwrapped.reserve(angles_deg.size());
  for (double a : angles_deg) unwrapped.push_back(mean - 90.0 + wrap180(a - (mean - 90.0)));
  return wrap180(median(unwrapped));
}

}  // namespace quadapt
