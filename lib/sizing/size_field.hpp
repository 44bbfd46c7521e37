#pragma once
// size-solve: the global size field (thesis §5.3 feature-based, §5.4 goal-oriented) and the
// frame M = V^-1 that lpcvt / bamgquad consume (eq. 3.13, docs/design.md §3-4).
//
// Continuous mesh model (eqs. 5.1-5.4): density d = 1/(4 h^2) (elements per unit area; the
// target element spans ±v, ±w, i.e. 2h1 x 2h2), continuous complexity
//     N_hp = ∫ d (p+1)^2 dx = Σ_k area_k d_k (p+1)^2        (d piecewise constant per cell).
//
// Feature-based (Problem 2, eq. 5.17): minimise ∫ B d^(-q n/2) subject to N_hp = C, n = p+1.
// Stationarity (corrected eq. 5.21, docs/design.md §4):
//     d = ( q B / (2 λ n) )^( 2/(q n + 2) ),  i.e. d ∝ B^(2/(qn+2)),
// so at the optimum B d^(-(qn+2)/2) = 2λn/q is the same in every cell. λ is found by bisection
// (in log space) on the monotone map λ -> N_hp, to a relative 1e-10 — also when safeguards
// (size bounds, gradation) are active, so the complexity still meets C.
//
// Goal-oriented (eqs. 5.22-5.25): target area I_k = α_k · area_k with α_k from the quadratic fit
// of the DWR indicator η_k in log space (r_max, c_max), η_ref by bisection so that N_hp = C;
// N_hp = (p+1)^2 Σ_k 1/α_k. Orientation and anisotropy still come from the SHAPE mesh.
//
// Safeguards (all stated in size-solve --help):
//  - anisotropy ρ = h1/h2 clamped to [1/ρ_max, ρ_max]; B is then re-evaluated from A1 and the
//    floored A2 >= A1 ρ_max^-(p+1) (estimate/error_model.hpp) when the SHAPE has A1, A2 — the
//    model's bound coefficients model_A1, model_A2 when it has them (estimate/polynomial_model.hpp);
//  - sizes in [hmin, hmax] (defaults 1e-6·sqrt(|Ω|) and 0.125·sqrt(|Ω|): the coarsest
//    element has a quarter of the domain's width, so a square gets at least 4 x 4 elements):
//    h = sqrt(h1 h2) is clamped there (re-solving λ), then ρ is capped so that every axis obeys
//    them too (h2 >= hmin, h1 <= hmax; d unchanged);
//  - optional gradation: h_k <= g · h_j for face neighbours j (g > 1; exact fixed point);
//  - B = 0 (no (p+1)-th derivative) gives the maximum size; B = 0 everywhere gives a uniform
//    density. Non-finite or negative inputs are InputErrors.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mesh/mesh.hpp"

namespace quadapt {

struct SizeOptions {
  double complexity = 0;       ///< target C (degrees of freedom), > 0
  double q = 2;                ///< L_q norm of the error model
  double max_anisotropy = 25;  ///< ρ_max (PHiLiP's per-axis [0.2, 5] for L_p-CVT = 25 in h1/h2)
  double hmin = 0;             ///< <= 0: 1e-6 sqrt(|Ω|)
  double hmax = 0;             ///< <= 0: 0.125 sqrt(|Ω|)
  double gradation = 0;        ///< max h ratio between face neighbours; 0 = off, else > 1
};

struct GoalOptions {
  double r_max = 20;  ///< maximum refinement factor (area divided by at most r_max)
  double c_max = 4;   ///< maximum coarsening factor (area multiplied by at most c_max)
};

struct SizeResult {
  int p = 0;
  std::vector<double> d;      ///< density per cell, 1/(4 h^2)
  std::vector<double> h;      ///< sqrt(h1 h2) per cell (half the target edge length)
  std::vector<double> theta;  ///< long-axis direction [0, π)
  std::vector<double> rho;    ///< h1/h2 after clamping
  std::vector<double> B;      ///< error constant used (feature-based)
  std::vector<double> alpha;  ///< area factors α_k (goal-oriented)
  double lambda = 0;          ///< Lagrange multiplier (feature-based)
  double eta_ref = 0;         ///< reference DWR (goal-oriented)
  double target_complexity = 0;
  double continuous_complexity = 0;
  double hmin = 0, hmax = 0;  ///< effective bounds
  int cells_at_hmin = 0, cells_at_hmax = 0, cells_anisotropy_capped = 0, cells_graded = 0;
  int iterations = 0;         ///< bisection steps
};

/// Per-cell SHAPE data read from a shape mesh (estimate-frame output).
struct ShapeData {
  int p = 0;
  std::vector<double> theta, rho, B, A1, A2;  ///< model_A1/2 (else A1/2); empty when the file has none
  std::vector<double> area;
};

/// Reads and checks the SHAPE fields (theta, rho, B, p; A1, A2 optional). `source` names the
/// file in InputError messages (missing field, non-finite value, negative B or ρ, mixed p).
ShapeData read_shape(const Mesh& shape, const std::string& source = "");

/// Continuous complexity Σ area_k d_k (p+1)^2.
double continuous_complexity(const std::vector<double>& area, const std::vector<double>& d, int p);

/// Feature-based size field (Problem 2). Throws InputError when C is outside what the size
/// bounds allow (e.g. C smaller than the coarsest admissible mesh carries).
SizeResult solve_feature_size(const Mesh& shape, const SizeOptions& opt, const std::string& source = "");

/// Goal-oriented size field from per-cell DWR indicators eta (>= 0), eqs. 5.22-5.25.
SizeResult solve_goal_size(const Mesh& shape, const std::vector<double>& eta, const SizeOptions& opt,
                           const GoalOptions& gopt, const std::string& source = "");

/// α_k of eqs. 5.24-5.25 (log-space quadratic fit), for eta_min <= eta_k <= eta_max, all > 0.
double goal_alpha(double eta_k, double eta_ref, double eta_min, double eta_max, double r_max, double c_max);

/// Throws InputError("dwr_source: ...") unless `dwr` has the same cells as `shape` (count and
/// centroids within 1e-8 of the domain size).
void check_same_cells(const Mesh& shape, const Mesh& dwr, const std::string& dwr_source);

/// The report figures of r (docs/size-solve.md): p, target and continuous complexity,
/// expected_cells, lambda (feature) or eta_ref and the alpha range (goal), the h range and
/// bounds, the capped/graded cell counts, bisection_iterations.
nlohmann::json to_json(const SizeResult& r);

}  // namespace quadapt
