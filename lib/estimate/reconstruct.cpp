#include "estimate/reconstruct.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <Eigen/LU>
#include <cmath>
#include <string>

#include "core/error.hpp"

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
    : mesh_(mesh), values_(values), p_(p), n_(n), basis_(p), rule_(gauss_legendre(n + 1)),
      exps_(monomial_exponents(n)) {
  if (p < 1 || n < 1) throw InputError("reconstruction: need p >= 1 and degree n >= 1");
  if (!mesh.all_quads()) throw InputError("reconstruction: the DG field needs an all-quad mesh");
  const size_t per = static_cast<size_t>(p + 1) * (p + 1);
  if (values.size() != per * mesh.cells.size())
    throw InputError("reconstruction: DG field has " + std::to_string(values.size()) +
                     " values, expected " + std::to_string(per * mesh.cells.size()) +
                     " ((p+1)^2 per cell, p = " + std::to_string(p) + ")");
}

PatchPolynomial PatchReconstructor::reconstruct(int cell, const std::vector<int>& patch) const {
  PatchPolynomial poly;
  poly.degree = n_;
  poly.center = cell_centroid(mesh_, cell);
  double H = 0;
  for (int c : patch)
    for (int k = 0; k < mesh_.cells[c].nv; ++k)
      H = std::max(H, (mesh_.nodes[mesh_.cells[c].v[k]] - poly.center).norm());
  if (!(H > 0)) throw NumericalError("reconstruction: degenerate patch around cell " + std::to_string(cell));
  poly.scale = H;

  const int nm = static_cast<int>(exps_.size());
  const int np1 = p_ + 1;
  const int nq = static_cast<int>(rule_.x.size());
  // 1D basis values/derivatives at the quadrature points: [q][i]
  std::vector<Eigen::VectorXd> lv(nq), ld(nq);
  for (int q = 0; q < nq; ++q) {
    lv[q] = basis_.eval(rule_.x[q]);
    ld[q] = basis_.deriv(rule_.x[q]);
  }
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(nm, nm);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(nm);
  Eigen::VectorXd m(nm), mx(nm), my(nm);
  std::vector<double> ps(n_ + 1), pt(n_ + 1);
  const double invH = 1.0 / H;

  for (int c : patch) {
    const double* u = values_.data() + static_cast<size_t>(c) * np1 * np1;
    for (int qj = 0; qj < nq; ++qj)
      for (int qi = 0; qi < nq; ++qi) {
        const double xi = rule_.x[qi], eta = rule_.x[qj];
        const Eigen::Matrix2d J = map_jacobian(mesh_, c, xi, eta);
        const double detJ = J.determinant();
        const double w = rule_.w[qi] * rule_.w[qj] * std::abs(detJ);
        // u and its reference gradient
        double uv = 0, ux = 0, ue = 0;
        for (int j = 0; j < np1; ++j)
          for (int i = 0; i < np1; ++i) {
            const double c0 = u[i + np1 * j];
            uv += c0 * lv[qi][i] * lv[qj][j];
            ux += c0 * ld[qi][i] * lv[qj][j];
            ue += c0 * lv[qi][i] * ld[qj][j];
          }
        // physical gradient = J^{-T} (du/dxi, du/deta)
        const Eigen::Vector2d g = J.transpose().partialPivLu().solve(Eigen::Vector2d(ux, ue));
        const Vec2 x = map_to_physical(mesh_, c, xi, eta);
        const double s = (x.x() - poly.center.x()) * invH, t = (x.y() - poly.center.y()) * invH;
        powers(s, n_, ps.data());
        powers(t, n_, pt.data());
        for (int k = 0; k < nm; ++k) {
          const int i = exps_[k].first, j = exps_[k].second;
          m[k] = ps[i] * pt[j];
          mx[k] = i > 0 ? i * ps[i - 1] * pt[j] * invH : 0.0;
          my[k] = j > 0 ? j * ps[i] * pt[j - 1] * invH : 0.0;
        }
        A.noalias() += w * (m * m.transpose() + mx * mx.transpose() + my * my.transpose());
        b.noalias() += w * (m * uv + mx * g.x() + my * g.y());
      }
  }
  Eigen::LDLT<Eigen::MatrixXd> ldlt(A);
  if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().minCoeff() > 0))
    throw NumericalError("reconstruction: singular H1 normal matrix on the patch of cell " +
                         std::to_string(cell));
  poly.coeffs = ldlt.solve(b);
  return poly;
}

}  // namespace quadapt
