#include "mesh/curved.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/error.hpp"

namespace quadapt {

void equispaced_lagrange(int q, double x, double* l, double* dl) {
  for (int i = 0; i <= q; ++i) {
    const double xi = -1 + 2.0 * i / q;
    double v = 1, d = 0;
    for (int m = 0; m <= q; ++m) {
      if (m == i) continue;
      const double xm = -1 + 2.0 * m / q;
      const double g = 1.0 / (xi - xm);
      const double f = (x - xm) * g;
      d = d * f + v * g;
      v *= f;
    }
    l[i] = v;
    dl[i] = d;
  }
}

int gmsh_quad_type(int q) {
  static const int type[] = {-1, 3, 10, 36, 37, 38, 47};
  return q >= 1 && q <= kMaxGeometricOrder ? type[q] : -1;
}
int gmsh_line_type(int q) {
  static const int type[] = {-1, 1, 8, 26, 27, 28, 62};
  return q >= 1 && q <= kMaxGeometricOrder ? type[q] : -1;
}

std::vector<int> edge_control_points(int q, int e) {
  const int n1 = q + 1;
  std::vector<int> idx(n1);
  for (int k = 0; k <= q; ++k) {
    int i, j;
    switch (e) {
      case 0: i = k; j = 0; break;
      case 1: i = q; j = k; break;
      case 2: i = q - k; j = q; break;
      default: i = 0; j = q - k; break;
    }
    idx[k] = i + n1 * j;
  }
  return idx;
}

std::vector<int> gmsh_quad_node_order(int q) {
  if (q < 1 || q > kMaxGeometricOrder)
    throw Error("gmsh_quad_node_order: order " + std::to_string(q) + " not supported");
  const int n1 = q + 1;
  std::vector<int> perm;
  // Gmsh orders a quad's nodes recursively: corners, edge interiors (in edge direction), then
  // the interior block [lo, hi]^2 as a quad of order hi - lo.
  for (int lo = 0, hi = q; lo <= hi; ++lo, --hi) {
    if (lo == hi) {
      perm.push_back(lo + n1 * lo);
      break;
    }
    const int ci[4] = {lo, hi, hi, lo}, cj[4] = {lo, lo, hi, hi};
    for (int k = 0; k < 4; ++k) perm.push_back(ci[k] + n1 * cj[k]);
    for (int e = 0; e < 4; ++e) {
      const int di = ci[(e + 1) % 4] > ci[e] ? 1 : ci[(e + 1) % 4] < ci[e] ? -1 : 0;
      const int dj = cj[(e + 1) % 4] > cj[e] ? 1 : cj[(e + 1) % 4] < cj[e] ? -1 : 0;
      for (int k = 1; k < hi - lo; ++k) perm.push_back(ci[e] + k * di + n1 * (cj[e] + k * dj));
    }
  }
  return perm;
}

CellMap::CellMap(const Mesh& m, int c) : q_(m.geometric_order()), X_(nullptr) {
  if (q_ > 1) {
    X_ = m.cell_points(c);
  } else {
    for (int k = 0; k < 4; ++k) corner_[k] = m.nodes[m.cells[c].v[k]];
  }
}

CellMap::CellMap(int q, const Vec2* X) : q_(q), X_(X) {
  if (q < 2 || q > kMaxGeometricOrder) throw Error("CellMap: order " + std::to_string(q) + " needs q in 2.." + std::to_string(kMaxGeometricOrder));
}

Vec2 CellMap::map(double xi, double eta) const {
  if (q_ == 1) {
    const double n0 = 0.25 * (1 - xi) * (1 - eta), n1 = 0.25 * (1 + xi) * (1 - eta);
    const double n2 = 0.25 * (1 + xi) * (1 + eta), n3 = 0.25 * (1 - xi) * (1 + eta);
    return corner_[0] * n0 + corner_[1] * n1 + corner_[2] * n2 + corner_[3] * n3;
  }
  double lx[kMaxGeometricOrder + 1], dlx[kMaxGeometricOrder + 1], ly[kMaxGeometricOrder + 1], dly[kMaxGeometricOrder + 1];
  equispaced_lagrange(q_, xi, lx, dlx);
  equispaced_lagrange(q_, eta, ly, dly);
  Vec2 x = Vec2::Zero();
  const int n1 = q_ + 1;
  for (int j = 0; j < n1; ++j)
    for (int i = 0; i < n1; ++i) x += X_[i + n1 * j] * (lx[i] * ly[j]);
  return x;
}

double CellMap::jacobian(double xi, double eta, Vec2& t1, Vec2& t2) const {
  if (q_ == 1) {
    const Vec2 &p0 = corner_[0], &p1 = corner_[1], &p2 = corner_[2], &p3 = corner_[3];
    t1 = 0.25 * ((p1 - p0) * (1 - eta) + (p2 - p3) * (1 + eta));
    t2 = 0.25 * ((p3 - p0) * (1 - xi) + (p2 - p1) * (1 + xi));
  } else {
    double lx[kMaxGeometricOrder + 1], dlx[kMaxGeometricOrder + 1], ly[kMaxGeometricOrder + 1], dly[kMaxGeometricOrder + 1];
    equispaced_lagrange(q_, xi, lx, dlx);
    equispaced_lagrange(q_, eta, ly, dly);
    t1.setZero();
    t2.setZero();
    const int n1 = q_ + 1;
    for (int j = 0; j < n1; ++j)
      for (int i = 0; i < n1; ++i) {
        const Vec2& X = X_[i + n1 * j];
        t1 += X * (dlx[i] * ly[j]);
        t2 += X * (lx[i] * dly[j]);
      }
  }
  return t1.x() * t2.y() - t1.y() * t2.x();
}

void edge_reference_point(int e, double s, double& xi, double& eta) {
  switch (e) {
    case 0: xi = -1 + 2 * s; eta = -1; break;
    case 1: xi = 1; eta = -1 + 2 * s; break;
    case 2: xi = 1 - 2 * s; eta = 1; break;
    default: xi = -1; eta = 1 - 2 * s; break;
  }
}

double edge_geometry(const CellMap& G, int e, double s, Vec2& x, Vec2& n) {
  double xi, eta;
  edge_reference_point(e, s, xi, eta);
  Vec2 t1, t2;
  G.jacobian(xi, eta, t1, t2);
  static const double dxi[4] = {2, 0, -2, 0}, deta[4] = {0, 2, 0, -2};
  const Vec2 T = t1 * dxi[e] + t2 * deta[e];
  const double len = T.norm();
  x = G.map(xi, eta);
  n = Vec2(T.y(), -T.x()) / len;
  return len;
}

void elevate_geometric_order(Mesh& m, int q) {
  if (q < 1 || q > kMaxGeometricOrder)
    throw Error("elevate_geometric_order: order " + std::to_string(q) + " not supported (1.." + std::to_string(kMaxGeometricOrder) + ")");
  if (m.is_curved()) throw Error("elevate_geometric_order: the mesh is already curved");
  if (!m.all_quads()) throw Error("elevate_geometric_order: curved cells must be quads");
  if (q == 1) return;
  const int n1 = q + 1;
  std::vector<Vec2> pts;
  pts.reserve(static_cast<size_t>(m.num_cells()) * n1 * n1);
  for (int c = 0; c < m.num_cells(); ++c) {
    CellMap G(m, c);
    for (int j = 0; j <= q; ++j)
      for (int i = 0; i <= q; ++i) {
        // Corners copied exactly (the map reproduces them only to rounding).
        const bool ci = i == 0 || i == q, cj = j == 0 || j == q;
        if (ci && cj) {
          const int k = j == 0 ? (i == 0 ? 0 : 1) : (i == 0 ? 3 : 2);
          pts.push_back(m.nodes[m.cells[c].v[k]]);
        } else {
          pts.push_back(G.map(-1 + 2.0 * i / q, -1 + 2.0 * j / q));
        }
      }
  }
  m.curved.order = q;
  m.curved.points = std::move(pts);
}

namespace {

/// Bernstein coefficients (degree n - 1 on [0, 1]) of the values f at the n equispaced points
/// t_k = k / (n - 1): the inverse of the collocation matrix B_j(t_k) (n <= 2 kMaxGeometricOrder),
/// by Gauss-Jordan with partial pivoting written out here: Eigen's dynamic-size LU
/// (PartialPivLU<MatrixXd>) is also instantiated and exported by Debian's libgmsh, and the
/// dynamic linker bound ours to its copy, built with another layout (AddressSanitizer: a heap
/// overflow inside compute_inverse when libgmsh was loaded).
Eigen::MatrixXd bernstein_from_values(int n) {
  std::vector<double> a(static_cast<size_t>(n) * 2 * n, 0.0);  // [V | I], row-major, 2n columns
  auto at = [&](int r, int c) -> double& { return a[static_cast<size_t>(r) * 2 * n + c]; };
  for (int k = 0; k < n; ++k) {
    const double t = n == 1 ? 0 : static_cast<double>(k) / (n - 1);
    for (int j = 0; j < n; ++j) {
      double binom = 1;
      for (int i = 0; i < j; ++i) binom = binom * (n - 1 - i) / (i + 1);
      at(k, j) = binom * std::pow(t, j) * std::pow(1 - t, n - 1 - j);
    }
    at(k, n + k) = 1;
  }
  for (int c = 0; c < n; ++c) {
    int piv = c;
    for (int r = c + 1; r < n; ++r)
      if (std::abs(at(r, c)) > std::abs(at(piv, c))) piv = r;
    for (int j = 0; j < 2 * n; ++j) std::swap(at(c, j), at(piv, j));
    const double d = at(c, c);
    for (int j = 0; j < 2 * n; ++j) at(c, j) /= d;
    for (int r = 0; r < n; ++r) {
      if (r == c || at(r, c) == 0) continue;
      const double f = at(r, c);
      for (int j = 0; j < 2 * n; ++j) at(r, j) -= f * at(c, j);
    }
  }
  Eigen::MatrixXd inv(n, n);
  for (int r = 0; r < n; ++r)
    for (int j = 0; j < n; ++j) inv(r, j) = at(r, n + j);
  return inv;
}

/// Halves the tensor Bernstein coefficients B (rows: eta index, columns: xi index) at 1/2 along
/// xi (dir 0) or eta (dir 1) by de Casteljau: the coefficients of the two halves.
void halve(const Eigen::MatrixXd& B, int dir, Eigen::MatrixXd& lo, Eigen::MatrixXd& hi) {
  const Eigen::MatrixXd A = dir == 0 ? B : Eigen::MatrixXd(B.transpose());
  const int rows = static_cast<int>(A.rows()), n = static_cast<int>(A.cols());
  Eigen::MatrixXd L(rows, n), H(rows, n);
  std::vector<double> w(n);
  for (int r = 0; r < rows; ++r) {
    for (int j = 0; j < n; ++j) w[j] = A(r, j);
    for (int level = 0; level < n; ++level) {
      L(r, level) = w[0];
      H(r, n - 1 - level) = w[n - 1 - level];
      for (int j = 0; j + 1 < n - level; ++j) w[j] = 0.5 * (w[j] + w[j + 1]);
    }
  }
  lo = dir == 0 ? L : Eigen::MatrixXd(L.transpose());
  hi = dir == 0 ? H : Eigen::MatrixXd(H.transpose());
}

void certify(const Eigen::MatrixXd& B, int depth, JacobianCertificate& r) {
  const int n = static_cast<int>(B.rows());
  const double corner = std::min({B(0, 0), B(0, n - 1), B(n - 1, 0), B(n - 1, n - 1)});
  if (corner <= 0) {  // det J's value at a point of the cell
    r.positive = false;
    r.lowest = std::min(r.lowest, corner);
    return;
  }
  r.lowest = std::min(r.lowest, corner);
  const double low = B.minCoeff();
  if (low > 0) return;
  if (depth == kCertifyDepth) {  // undecided: det J is positive at every point met, down to 1/4096 of the cell
    r.undecided = true;
    return;
  }
  Eigen::MatrixXd a, b;
  halve(B, depth % 2, a, b);
  certify(a, depth + 1, r);
  if (r.positive) certify(b, depth + 1, r);
}

}  // namespace

JacobianCertificate certify_jacobian(const Mesh& m, int c) {
  JacobianCertificate r;
  const int q = m.geometric_order(), n = 2 * q;
  r.lowest = std::numeric_limits<double>::infinity();
  if (q < 2 || !m.cells[c].is_quad()) return r;
  thread_local int cached_n = -1;
  thread_local Eigen::MatrixXd Vinv;
  if (cached_n != n) {
    Vinv = bernstein_from_values(n);
    cached_n = n;
  }
  CellMap G(m, c);
  Eigen::MatrixXd F(n, n);  // F(j, i) = det J at (xi_i, eta_j)
  Vec2 t1, t2;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) F(j, i) = G.jacobian(-1 + 2.0 * i / (n - 1), -1 + 2.0 * j / (n - 1), t1, t2);
  certify(Vinv * F * Vinv.transpose(), 0, r);
  return r;
}

ScaledJacobian min_scaled_jacobian(const Mesh& m) {
  ScaledJacobian r;
  const int q = m.geometric_order(), n = 2 * q + 2;
  for (int c = 0; c < m.num_cells(); ++c) {
    if (!m.cells[c].is_quad()) continue;
    CellMap G(m, c);
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    Vec2 t1, t2;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double d = G.jacobian(-1 + 2.0 * i / (n - 1), -1 + 2.0 * j / (n - 1), t1, t2);
        lo = std::min(lo, d);
        hi = std::max(hi, d);
      }
    double s = hi > 0 ? lo / hi : -1;
    if (s > 0 && q >= 2) {  // the samples may miss a fold between them: certify
      const JacobianCertificate cert = certify_jacobian(m, c);
      if (!cert.positive) s = std::min(0.0, cert.lowest / hi);
    }
    if (r.cell < 0 || s < r.min) {
      r.min = s;
      r.cell = c;
    }
  }
  return r;
}

}  // namespace quadapt
