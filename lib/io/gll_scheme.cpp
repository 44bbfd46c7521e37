#include "io/gll_scheme.hpp"

#include <cctype>
#include <stdexcept>

#include "fem/basis.hpp"

namespace quadapt {

namespace {
const char* const kPrefix = "quadapt_gll_p";

// Monomial coefficients c[a] of the 1D Lagrange polynomial l_i through `x`:
// l_i(t) = prod_{m != i} (t - x_m) / (x_i - x_m), expanded by repeated multiplication.
std::vector<double> lagrange_monomials(const std::vector<double>& x, int i) {
  const int n = static_cast<int>(x.size());
  std::vector<double> c(n, 0.0);
  c[0] = 1.0;
  int deg = 0;
  double denom = 1.0;
  for (int m = 0; m < n; ++m) {
    if (m == i) continue;
    // multiply by (t - x_m)
    for (int a = deg + 1; a >= 1; --a) c[a] = c[a - 1] - x[m] * c[a];
    c[0] = -x[m] * c[0];
    ++deg;
    denom *= x[i] - x[m];
  }
  for (double& v : c) v /= denom;
  return c;
}
}  // namespace

std::string gll_scheme_name(int p) { return kPrefix + std::to_string(p); }

int parse_gll_scheme_name(const std::string& name) {
  const std::string prefix = kPrefix;
  if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) return -1;
  int p = 0;
  for (size_t k = prefix.size(); k < name.size(); ++k) {
    if (!std::isdigit(static_cast<unsigned char>(name[k]))) return -1;
    p = 10 * p + (name[k] - '0');
    if (p > 64) return -1;
  }
  return p;
}

GmshInterpolation gll_interpolation(int p) {
  if (p < 0) throw std::invalid_argument("gll_interpolation: p >= 0");
  const int q = p + 1;
  std::vector<double> x = p == 0 ? std::vector<double>{0.0} : LagrangeBasis1D(p).nodes();
  std::vector<std::vector<double>> c1(q);
  for (int i = 0; i < q; ++i) c1[i] = lagrange_monomials(x, i);
  GmshInterpolation g;
  g.n = q * q;
  g.coef.assign(static_cast<size_t>(g.n) * g.n, 0.0);
  g.exp.assign(static_cast<size_t>(g.n) * 3, 0.0);
  for (int j = 0; j < q; ++j)
    for (int i = 0; i < q; ++i) {
      const int k = i + q * j;
      for (int b = 0; b < q; ++b)
        for (int a = 0; a < q; ++a) g.coef[static_cast<size_t>(k) * g.n + a + q * b] = c1[i][a] * c1[j][b];
    }
  for (int b = 0; b < q; ++b)
    for (int a = 0; a < q; ++a) {
      const int m = a + q * b;
      g.exp[3 * m] = a;
      g.exp[3 * m + 1] = b;
    }
  return g;
}

}  // namespace quadapt
