#include "estimate/reconstruct.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "mesh/label.hpp"

namespace quadapt {

std::vector<std::pair<int, int>> monomial_exponents(int n) {
  std::vector<std::pair<int, int>> e;
  for (int k = 0; k <= n; ++k)
    for (int i = k; i >= 0; --i) e.emplace_back(i, k - i);
  return e;
}

namespace {
// powers[k] = v^k, k = 0..n
inline void powers(double v, int n, double* out) {
  out[0] = 1;
  for (int k = 1; k <= n; ++k) out[k] = out[k - 1] * v;
}
}  // namespace

double PatchPolynomial::eval(const Vec2& x) const {
  const double s = (x.x() - center.x()) / scale, t = (x.y() - center.y()) / scale;
  std::vector<double> ps(degree + 1), pt(degree + 1);
  powers(s, degree, ps.data());
  powers(t, degree, pt.data());
  auto e = monomial_exponents(degree);
  double v = 0;
  for (size_t k = 0; k < e.size(); ++k) v += coeffs[k] * ps[e[k].first] * pt[e[k].second];
  return v;
}

std::vector<double> PatchPolynomial::top_homogeneous() const {
  std::vector<double> a(degree + 1, 0.0);
  auto e = monomial_exponents(degree);
  const double f = std::pow(scale, -degree);
  for (size_t k = 0; k < e.size(); ++k)
    if (e[k].first + e[k].second == degree) a[e[k].first] = coeffs[k] * f;
  return a;
}

PatchReconstructor::PatchReconstructor(const Mesh& mesh, const std::vector<double>& values, int p,
                                       int n)
    : mesh_(mesh), p_(p), n_(n), rule_(gauss_legendre(std::max(n, 1) + 1)), exps_(monomial_exponents(n)) {
  if (p < 1 || n < 1) throw InputError("reconstruction: need p >= 1 and degree n >= 1");
  if (!mesh.all_quads()) throw InputError("reconstruction: the DG field needs an all-quad mesh");
  const int np1 = p + 1;
  const size_t per = static_cast<size_t>(np1) * np1;
  if (values.size() != per * mesh.cells.size())
    throw InputError("reconstruction: DG field has " + std::to_string(values.size()) +
                     " values, expected " + std::to_string(per * mesh.cells.size()) +
                     " ((p+1)^2 per cell, p = " + std::to_string(p) + ")");
  const int nq1 = static_cast<int>(rule_.x.size());
  nq_ = nq1 * nq1;
  LagrangeBasis1D basis(p);
  std::vector<Eigen::VectorXd> lv(nq1), ld(nq1);
  for (int q = 0; q < nq1; ++q) {
    lv[q] = basis.eval(rule_.x[q]);
    ld[q] = basis.deriv(rule_.x[q]);
  }
  const int nc = mesh.num_cells();
  length_ = domain_length(mesh);
  qdata_.resize(static_cast<size_t>(nc) * nq_ * 6);
#pragma omp parallel for schedule(static)
  for (int c = 0; c < nc; ++c) {
    const double* u = values.data() + static_cast<size_t>(c) * per;
    double* out = qdata_.data() + static_cast<size_t>(c) * nq_ * 6;
    for (int qj = 0; qj < nq1; ++qj)
      for (int qi = 0; qi < nq1; ++qi, out += 6) {
        const double xi = rule_.x[qi], eta = rule_.x[qj];
        const Eigen::Matrix2d J = map_jacobian(mesh, c, xi, eta);
        const double det = J(0, 0) * J(1, 1) - J(0, 1) * J(1, 0);
        double uv = 0, ux = 0, ue = 0;
        for (int j = 0; j < np1; ++j)
          for (int i = 0; i < np1; ++i) {
            const double c0 = u[i + np1 * j];
            uv += c0 * lv[qi][i] * lv[qj][j];
            ux += c0 * ld[qi][i] * lv[qj][j];
            ue += c0 * lv[qi][i] * ld[qj][j];
          }
        // physical gradient = J^{-T} (du/dxi, du/deta)
        const double gx = (J(1, 1) * ux - J(1, 0) * ue) / det;
        const double gy = (-J(0, 1) * ux + J(0, 0) * ue) / det;
        const Vec2 x = map_to_physical(mesh, c, xi, eta);
        out[0] = x.x();
        out[1] = x.y();
        out[2] = std::sqrt(rule_.w[qi] * rule_.w[qj] * std::abs(det));
        out[3] = uv;
        out[4] = gx;
        out[5] = gy;
      }
  }
}

double domain_length(const Mesh& mesh) {
  double area = 0;
  for (int c = 0; c < mesh.num_cells(); ++c) area += std::abs(cell_area(mesh, c));
  if (!(area > 0) || !std::isfinite(area)) return 1;
  return std::exp2(std::floor(0.5 * std::log2(area) + 0.5));  // ties up, so L(2^k x) = 2^k L(x)
}

PatchPolynomial PatchReconstructor::reconstruct(int cell, const std::vector<int>& patch) const {
  PatchPolynomial poly;
  poly.degree = n_;
  poly.center = cell_centroid(mesh_, cell);
  double H = 0;
  for (int c : patch)
    for (int k = 0; k < mesh_.cells[c].nv; ++k)
      H = std::max(H, (mesh_.nodes[mesh_.cells[c].v[k]] - poly.center).norm());
  if (!(H > 0)) throw NumericalError("reconstruction: degenerate patch around " + cell_label(mesh_, cell));
  poly.scale = H;

  const int nm = static_cast<int>(exps_.size());
  const int rows = 3 * nq_ * static_cast<int>(patch.size());
  Eigen::MatrixXd G(rows, nm);
  Eigen::VectorXd f(rows);
  std::vector<double> ps(n_ + 1), pt(n_ + 1);
  const double invH = 1.0 / H;
  int r = 0;
  for (int c : patch) {
    const double* q = qdata_.data() + static_cast<size_t>(c) * nq_ * 6;
    for (int k = 0; k < nq_; ++k, q += 6, r += 3) {
      const double s = (q[0] - poly.center.x()) * invH, t = (q[1] - poly.center.y()) * invH, sw = q[2];
      const double swL = sw * length_;  // the gradient rows' weight: L^2 in the squared norm
      powers(s, n_, ps.data());
      powers(t, n_, pt.data());
      for (int m = 0; m < nm; ++m) {
        const int i = exps_[m].first, j = exps_[m].second;
        G(r, m) = sw * ps[i] * pt[j];
        G(r + 1, m) = i > 0 ? swL * i * ps[i - 1] * pt[j] * invH : 0.0;
        G(r + 2, m) = j > 0 ? swL * j * ps[i] * pt[j - 1] * invH : 0.0;
      }
      f[r] = sw * q[3];
      f[r + 1] = swL * q[4];
      f[r + 2] = swL * q[5];
    }
  }
  Eigen::HouseholderQR<Eigen::MatrixXd> qr(G);
  const auto R = qr.matrixQR().topRows(nm).diagonal().cwiseAbs();
  if (!(R.minCoeff() > 1e-13 * R.maxCoeff()))
    throw NumericalError("reconstruction: rank-deficient H1 problem on the patch of " + cell_label(mesh_, cell));
  poly.coeffs = qr.solve(f);
  return poly;
}

}  // namespace quadapt
