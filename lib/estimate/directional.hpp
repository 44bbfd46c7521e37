#pragma once
// Extremal (p+1)-th directional derivatives of a homogeneous polynomial (thesis eqs. 5.10-5.13).
//
// Given the top-degree part of the reconstruction, P(y) = Σ_{i=0..n} a_i y_x^i y_y^(n-i)
// (n = p+1, a from PatchPolynomial::top_homogeneous), the directional error term along the unit
// vector ξ = (cos φ, sin φ) is P(ξ) = D^n u[ξ,...,ξ] / n! (eqs. 5.6-5.7, the convention PHiLiP
// uses). Then
//   A1 = max_φ |P(ξ(φ))|,  φ1 = argmax in [0, π)   (|P| is π-periodic),
//   A2 = |P(ξ(φ1 + π/2))|                          (perpendicular direction, eq. 5.13).
// The maximum is found by sampling max(120, 60 n) directions and refining the best sample by bisection on the
// zero of dP/dφ (to ~1e-15 rad). When several directions tie (to rounding) the smallest φ wins.
// All values are >= 0 and finite for finite input; a = 0 gives A1 = A2 = 0, φ1 = 0.
#include <vector>

namespace quadapt {

struct DirectionalExtrema {
  double A1 = 0;   ///< largest |P(ξ)|, units of u / length^n
  double A2 = 0;   ///< |P| perpendicular to the maximising direction
  double phi = 0;  ///< direction of A1, radians in [0, π)
};

/// P(cos φ, sin φ) for coefficients a (a[i] multiplies x^i y^(n-i), n = a.size() - 1).
double directional_value(const std::vector<double>& a, double phi);

/// dP(cos φ, sin φ)/dφ.
double directional_derivative(const std::vector<double>& a, double phi);

/// A1, A2, φ of eqs. 5.10-5.13 for the homogeneous polynomial with coefficients a.
DirectionalExtrema directional_extrema(const std::vector<double>& a);

}  // namespace quadapt
