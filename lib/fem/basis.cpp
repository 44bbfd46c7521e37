#include "fem/basis.hpp"

#include <cmath>
#include <stdexcept>

namespace quadapt {

namespace {
// Legendre polynomial P_n and its derivative at x (three-term recurrence).
void legendre(int n, double x, double& p, double& dp) {
  double p0 = 1, p1 = x;
  if (n == 0) { p = 1; dp = 0; return; }
  for (int k = 2; k <= n; ++k) {
    double pk = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
    p0 = p1;
    p1 = pk;
  }
  p = p1;
  dp = (std::abs(x) < 1) ? n * (x * p1 - p0) / (x * x - 1) : 0.5 * n * (n + 1) * std::pow(x, n + 1);
}
}  // namespace

Rule1D gauss_legendre(int n) {
  if (n < 1) throw std::invalid_argument("gauss_legendre: n >= 1");
  Rule1D r;
  r.x.resize(n);
  r.w.resize(n);
  for (int i = 0; i < n; ++i) {
    double x = -std::cos(M_PI * (i + 0.75) / (n + 0.5));
    for (int it = 0; it < 100; ++it) {
      double p, dp;
      legendre(n, x, p, dp);
      double dx = p / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    double p, dp;
    legendre(n, x, p, dp);
    r.x[i] = x;
    r.w[i] = 2.0 / ((1 - x * x) * dp * dp);
  }
  return r;
}

Rule1D gauss_lobatto(int n) {
  if (n < 2) throw std::invalid_argument("gauss_lobatto: n >= 2");
  Rule1D r;
  r.x.resize(n);
  r.w.resize(n);
  const int N = n - 1;  // interior points are roots of P_N'
  r.x[0] = -1;
  r.x[N] = 1;
  r.w[0] = r.w[N] = 2.0 / (N * (N + 1));
  for (int i = 1; i < N; ++i) {
    double x = -std::cos(M_PI * i / N);
    for (int it = 0; it < 100; ++it) {
      // Newton on q(x) = P_N'(x), q' = (2x P_N' - N(N+1) P_N)/(1-x^2)
      double p, dp;
      legendre(N, x, p, dp);
      double ddp = (2 * x * dp - N * (N + 1) * p) / (1 - x * x);
      double dx = dp / ddp;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    double p, dp;
    legendre(N, x, p, dp);
    r.x[i] = x;
    r.w[i] = 2.0 / (N * (N + 1) * p * p);
  }
  // Symmetrise to remove round-off asymmetry.
  for (int i = 0; i < n / 2; ++i) {
    double x = 0.5 * (r.x[n - 1 - i] - r.x[i]);
    double w = 0.5 * (r.w[n - 1 - i] + r.w[i]);
    r.x[i] = -x; r.x[n - 1 - i] = x;
    r.w[i] = r.w[n - 1 - i] = w;
  }
  if (n % 2 == 1) r.x[n / 2] = 0;
  return r;
}

LagrangeBasis1D::LagrangeBasis1D(int p) : p_(p) {
  if (p < 1) throw std::invalid_argument("LagrangeBasis1D: degree >= 1");
  nodes_ = gauss_lobatto(p + 1).x;
  bary_.assign(p + 1, 1.0);
  for (int i = 0; i <= p; ++i)
    for (int j = 0; j <= p; ++j)
      if (i != j) bary_[i] /= (nodes_[i] - nodes_[j]);
}

Eigen::VectorXd LagrangeBasis1D::eval(double x) const {
  Eigen::VectorXd l(p_ + 1);
  for (int i = 0; i <= p_; ++i) {
    double v = 1;
    for (int j = 0; j <= p_; ++j)
      if (j != i) v *= (x - nodes_[j]) / (nodes_[i] - nodes_[j]);
    l[i] = v;
  }
  return l;
}

Eigen::VectorXd LagrangeBasis1D::deriv(double x) const {
  // d/dx prod_{j!=i} (x - x_j)/(x_i - x_j) = sum_{k!=i} [1/(x_i-x_k)] prod_{j!=i,k} (x-x_j)/(x_i-x_j)
  Eigen::VectorXd d = Eigen::VectorXd::Zero(p_ + 1);
  for (int i = 0; i <= p_; ++i) {
    double s = 0;
    for (int k = 0; k <= p_; ++k) {
      if (k == i) continue;
      double prod = 1.0 / (nodes_[i] - nodes_[k]);
      for (int j = 0; j <= p_; ++j)
        if (j != i && j != k) prod *= (x - nodes_[j]) / (nodes_[i] - nodes_[j]);
      s += prod;
    }
    d[i] = s;
  }
  return d;
}

double eval_tensor(const LagrangeBasis1D& b, const double* u, double xi, double eta) {
  Eigen::VectorXd lx = b.eval(xi), ly = b.eval(eta);
  const int n = b.size();
  double s = 0;
  for (int j = 0; j < n; ++j) {
    double row = 0;
    for (int i = 0; i < n; ++i) row += u[i + n * j] * lx[i];
    s += row * ly[j];
  }
  return s;
}

}  // namespace quadapt
