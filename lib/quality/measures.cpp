#include "quality/measures.hpp"

#include <algorithm>
#include <cmath>

#include "fem/basis.hpp"
#include "mesh/curved.hpp"

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

namespace {
// The control points of curved cell c, mapped by M when given.
std::vector<Vec2> control_points(const Mesh& m, int c, const Eigen::Matrix2d* M) {
  const Vec2* X = m.cell_points(c);
  std::vector<Vec2> P(X, X + m.curved.per_cell());
  if (M)
    for (Vec2& x : P) x = *M * x;
  return P;
}

double edge_length(const CellMap& G, int e) {
  static const Rule1D g = gauss_legendre(8);
  double len = 0;
  Vec2 x, n;
  for (size_t k = 0; k < g.x.size(); ++k) len += 0.5 * g.w[k] * edge_geometry(G, e, 0.5 * (g.x[k] + 1), x, n);
  return len;
}
}  // namespace

double curved_edge_length(const Mesh& m, int c, int e, const Eigen::Matrix2d* M) {
  const std::vector<Vec2> P = control_points(m, c, M);
  return edge_length(CellMap(m.geometric_order(), P.data()), e);
}

CellShape curved_cell_shape(const Mesh& m, int c, const Eigen::Matrix2d* M) {
  const int q = m.geometric_order();
  const std::vector<Vec2> P = control_points(m, c, M);
  const CellMap G(q, P.data());
  CellShape s;
  s.nv = 4;
  s.scaled_jacobian = INFINITY;
  s.edge_min = INFINITY;
  s.edge_max = 0;
  // corners (xi, eta) of v[0..3]; the tangent along the next edge and back along the previous
  // one are +-dx/dxi, +-dx/deta
  static const double cx[4] = {-1, 1, 1, -1}, cy[4] = {-1, -1, 1, 1};
  Vec2 t1, t2;
  for (int i = 0; i < 4; ++i) {
    G.jacobian(cx[i], cy[i], t1, t2);
    const Vec2 T[4] = {t1, t2, Vec2(-t1), Vec2(-t2)};  // edge i's direction from v[i] is T[i]
    const Vec2 en = T[i], ep = -T[(i + 3) % 4];
    double a = std::atan2(cross(en, ep), en.dot(ep)) * 180.0 / M_PI;
    if (a < 0) a += 360.0;
    s.angle_deg[i] = a;
    const double ln = edge_length(G, i);
    if (ln < s.edge_min) s.edge_min = ln;
    if (ln > s.edge_max) {
      s.edge_max = ln;
      const std::vector<int> idx = edge_control_points(q, i);
      const Vec2 chord = P[idx.back()] - P[idx.front()];
      s.orientation_deg = wrap180(std::atan2(chord.y(), chord.x()) * 180.0 / M_PI);
    }
  }
  const int n = 2 * q + 2;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double det = G.jacobian(-1 + 2.0 * i / (n - 1), -1 + 2.0 * j / (n - 1), t1, t2);
      const double l1 = t1.norm(), l2 = t2.norm();
      s.scaled_jacobian = std::min(s.scaled_jacobian, l1 > 0 && l2 > 0 ? det / (l1 * l2) : 0.0);
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
