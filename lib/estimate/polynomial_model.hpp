#pragma once
// The polynomial error model: the element's stretch and error constant from the whole
// degree-(p+1) Taylor term, not only from its values along two perpendicular directions
// (docs/estimate-frame.md, *Error models*).
//
// P(y) = Σ_{i=0..n} a_i y_x^i y_y^(n-i) is the top-degree part of the patch reconstruction
// (n = p+1; directional.hpp's convention: P(ξ) = D^n u[ξ,...,ξ] / n!). The thesis's model
// (eqs. 5.9-5.16, error_model.hpp) replaces |P(y)| by the metric bound (yᵀ Q y)^(n/2) whose values
// along φ1 (the direction of A1 = max |P|) and across it are A1 and A2 = |P(φ1 + π/2)|. For odd n
// that bound vanishes across φ1 wherever P does, whatever P's other terms: the n-th derivatives of
// a harmonic function give P(φ) ∝ cos(nφ − ψ), whose value across the maximum is cos(nπ/2) = 0,
// so the thesis's model asks for ρ = its cap everywhere although, with the mixed terms counted, the
// best element is the square. This model integrates |P| itself.
//
// With the element's circumscribed ellipse Σ as in error_model.hpp (half-axes √2 h1 along the
// long axis v = (cos θ, sin θ), √2 h2 along w, h1 h2 = h², ρ = h1/h2, element area 4h² = 1/d),
// the error per unit area is
//     e = (1 / 4h²) ∫_Σ |P(y)|^q dy = 2^(-(qn+2)/2) / (qn + 2) · I(θ, ρ) · d^(-qn/2),
//     I(θ, ρ) = ∫_0^{2π} |P(R(θ) diag(√ρ, 1/√ρ) (cos φ, sin φ))|^q dφ,
// so the best stretch at the long axis θ minimises I over ρ ∈ [1, ρ_max], and the error constant
// is B = 2^(-(qn+2)/2) / (qn + 2) · min I. For q = 2, with b_k(θ) the coefficients of P in the
// rotated frame (P(R(θ)ξ) = Σ b_k ξ1^k ξ2^(n-k)),
//     I(θ, ρ) = Σ_{j=0..n} ρ^(2j-n) G_{2j} Σ_{k+l=2j} b_k b_l,
//     G_m = ∫_0^{2π} cos^m φ sin^(2n-m) φ dφ = 2π (m-1)!! (2n-m-1)!! / (2n)!!   (m even),
// a closed form in ρ; other q integrate over φ numerically (64 + 8n directions).
//
// The orientation stays the thesis's (θ = φ1 − π/2, the short axis along the largest derivative):
// minimising I over θ as well moves θ to cancel the reconstruction's noise in the mixed terms
// (front normals 2.5–4.4° off in the median where φ1 is 0.6–1.1° off) and lost 1.25–1.45× on the
// boundary-layer studies (docs/estimate-frame.md).
//
// Where the thesis's bound is exact — n = 2 with a definite Hessian — the two models give the same
// ρ and B (unit test); for P = A (y·e)^n both stretch to the cap and B differs by the constant
// factor ∫|sin φ|^(qn) dφ / 2π. The fit is expressed through the thesis's fields: the equivalent
// bound coefficients A1 A2 = (I_min / 2π)^(2/q), A1 / A2 = ρ^n, φ = θ + π/2 reproduce θ, ρ and B
// through error_model.hpp's formulas, so size-solve's anisotropy cap, which re-evaluates B from A1
// and A2 (effective_A2), works unchanged; that re-evaluation is the thesis's bound at the cap,
// the true integral there when P = A (y·e)^n.
#include <vector>

namespace quadapt {

/// I(θ, ρ) above for coefficients a (a[i] multiplies x^i y^(n-i)), θ the long axis, ρ > 0, q >= 1.
double polynomial_shape_integral(const std::vector<double>& a, double theta, double rho, double q);

struct PolynomialShape {
  double theta = 0;  ///< long axis (the input θ), radians in [0, π)
  double rho = 1;    ///< h1/h2 in [1, rho_max]
  double I = 0;      ///< min over ρ of I(θ, ρ), units (u / length^n)^q
  double A1 = 0;     ///< equivalent bound coefficients (see the header comment)
  double A2 = 0;
  double phi = 0;    ///< θ + π/2 wrapped to [0, π): the direction of A1 (the short axis)
};

/// The minimiser of I over ρ ∈ [1, rho_max] at the long axis θ: a grid of 32 steps in log ρ, then
/// a golden-section search on the two steps around the best grid point, to 1e-9 in log ρ.
/// Ties go to the smaller ρ; a = 0 returns I = 0, ρ = 1.
PolynomialShape polynomial_stretch(const std::vector<double>& a, double q, double rho_max, double theta);

}  // namespace quadapt
