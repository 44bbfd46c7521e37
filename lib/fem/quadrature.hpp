#pragma once
// Quadrature rules on triangles (used by the L_p-CVT energy and metric areas) (thesis eq. 4.8, "quadrature rules on
// the reference triangle f'"). A rule is a list of barycentric points and weights summing to 1,
// so  integral over T of f  ~=  area(T) * sum_q w_q f(sum_a bary_q[a] * T_a).
#include <array>
#include <vector>

namespace quadapt {

struct TriangleRule {
  std::vector<std::array<double, 3>> bary;  ///< barycentric coordinates of the points
  std::vector<double> w;                    ///< weights, sum 1
  int degree = 0;                           ///< polynomials of this total degree are exact
  int size() const { return static_cast<int>(w.size()); }
};

/// Dunavant's 12-point rule, exact for degree 6 (so exact for the L_6 energy of a constant
/// metric: |M (y - x)|_6^6 is a degree-6 polynomial in y).
const TriangleRule& dunavant6();

/// Collapsed (Duffy) Gauss-Legendre rule exact for total degree `degree` (any degree >= 0):
/// ceil((degree+2)/2) x ceil((degree+1)/2) points. Used for analytic metrics and as a check.
TriangleRule collapsed_gauss(int degree);

/// The rule used for the L_p energy of exponent p: dunavant6 for p <= 6 (exact for even p
/// with a constant metric), otherwise collapsed_gauss(ceil(p)).
const TriangleRule& rule_for_exponent(double p);

}  // namespace quadapt
