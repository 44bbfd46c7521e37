#include "estimate/error_model.hpp"

#include <algorithm>
#include <cmath>

namespace quadapt {

double wrap_pi(double a) {
  double r = std::fmod(a, M_PI);
  if (r < 0) r += M_PI;
  if (r >= M_PI) r -= M_PI;
  return r;
}

double effective_A2(double A1, double A2, int n, double rho_max) {
  const double floor = A1 * std::pow(rho_max, -static_cast<double>(n));
  return std::max(A2, floor);
}

double error_constant(double A1, double A2, int n, double q) {
  const double qn2 = q * n + 2;
  const double prod = std::max(0.0, A1) * std::max(0.0, A2);
  return 2 * M_PI / qn2 * std::pow(2.0, -qn2 / 2) * std::pow(prod, q / 2);
}

FrameShape optimal_shape(double A1, double A2, double phi, int n, double q, double rho_max) {
  FrameShape s;
  if (!(A1 > 0) || !std::isfinite(A1)) return s;  // isotropic, B = 0
  A2 = std::min(effective_A2(A1, A2, n, rho_max), A1);
  s.theta = wrap_pi(phi - 0.5 * M_PI);
  s.rho = std::min(std::pow(A1 / A2, 1.0 / n), rho_max);
  s.B = error_constant(A1, A2, n, q);
  return s;
}

}  // namespace quadapt
