#pragma once
// estimate-frame: per-cell optimal frame shape and error constant from a DG solution
// (thesis Algorithm 4, "local error minimization": eqs. 5.8, 5.10-5.16).
//
// For each cell k: the degree-(p+1) H1 patch reconstruction over k and its face neighbours
// (estimate/reconstruct.hpp), the extremal (p+1)-th directional derivatives A1, A2 and the
// direction φ of A1 (estimate/directional.hpp), then θ, ρ, B: by default from the whole
// top-degree term (estimate/polynomial_model.hpp), or by the thesis's bound (estimate/error_model.hpp).
// Cells are independent: OpenMP-parallel, deterministic for any thread count.
#include <string>
#include <vector>

#include "mesh/mesh.hpp"

namespace quadapt {

/// Reconstruction patch D(k): Face = k and its face neighbours (thesis Fig. 5.1, the default);
/// Vertex = k and every cell sharing a vertex with it, plus face neighbours (hanging nodes)
/// — a tensor-like 3x3 patch on structured meshes, less biased at boundaries.
enum class PatchKind { Face, Vertex };

/// The local error model that turns the top-degree term P into θ, ρ, B:
/// Polynomial = the L_q integral of |P| itself over the element (polynomial_model.hpp, the default);
/// Thesis = the thesis's bound from A1 and A2 = |P| across A1's direction (eqs. 5.9-5.16).
enum class ErrorModel { Polynomial, Thesis };

struct EstimateOptions {
  std::string field = "u";    ///< name of the DG CellNodeField
  PatchKind patch = PatchKind::Face;
  ErrorModel model = ErrorModel::Polynomial;
  double q = 2;               ///< L_q norm of the error model (q >= 1)
  /// Numerical cap on ρ = h1/h2 (and floor A2 >= A1 ρ_max^-(p+1)) so that A2 = 0 stays finite.
  /// The user-facing anisotropy limit is size-solve's --max-anisotropy.
  double max_anisotropy = 1e6;
  /// Observed-error floor τ (0 = off): where the reconstruction's misfit ||ũ − u_h||^q_{L_q(K)}
  /// over the model's error at the cell's current size, e_K = B_K |K|^((q(p+1)+2)/2), exceeds τ
  /// times its median over the cells, B_K is raised by that excess, at most 64× (docs/estimate-frame.md
  /// *Observed-error floor*): the Taylor model under-predicts singular and unresolved cells.
  double observed_floor = 4;
  /// Noise floor: cells with A1 h_k^(p+1) <= max(direction_floor · (max u − min u) / 2, R_K) (h_k =
  /// sqrt(cell area)) or A1 <= direction_floor · max_k A1 are derivative-free: A1 = A2 = B = 0,
  /// θ = 0, ρ = 1. R_K = 1e3 ε max|u_h| over the cell's patch × s_K^((p+1)/2), s_K = longest edge² /
  /// area (a stretched cell's fit amplifies rounding across it), is the fit's rounding; the
  /// observed-error floor ignores cells whose misfit is at that level, R_K^q |K|.
  double direction_floor = 1e-10;
};

struct EstimateResult {
  int p = 0;                  ///< DG degree of the input field
  std::vector<double> A1, A2; ///< eq. 5.10, 5.13 (Taylor-term convention, see directional.hpp)
  /// The thesis-bound coefficients that reproduce the model's ρ and B through error_model.hpp
  /// (size-solve re-evaluates B from them at its anisotropy cap): A1, A2 with ErrorModel::Thesis;
  /// with ErrorModel::Polynomial A1 A2 = (I/2π)^(2/q), A1/A2 = ρ^n (polynomial_model.hpp).
  std::vector<double> model_A1, model_A2;
  std::vector<double> phi;    ///< direction of A1 (the short axis), [0, π)
  std::vector<double> theta;  ///< long-axis direction, [0, π)
  std::vector<double> rho;    ///< h1/h2 >= 1
  std::vector<double> B;      ///< error constant (eq. 5.16, our constant; raised by the observed floor)
  std::vector<double> misfit; ///< ||ũ − u_h||^q_{L_q(K)} by the cell's GLL nodes (mean |·|^q × area)
  double misfit_ratio_median = 0;  ///< κ: the median of misfit / (B |K|^((qn+2)/2)) over cells with B > 0
  int cells_raised = 0;            ///< cells whose B the observed floor raised
};

/// The patch cells of every cell (cell k first, then the others in increasing index).
std::vector<std::vector<int>> reconstruction_patches(const Mesh& m, PatchKind kind);

/// Runs the estimate on `sol`, straight or curved (mesh/curved.hpp): the DG field's values sit
/// at the GLL points of each cell's map, and the reconstruction integrates on that map
/// (map_to_physical, map_jacobian), so curved cells give the derivatives of the field on the
/// true cells. `source` names the file in error messages. Throws InputError
/// when the field is missing or is not a degree-p DG field on an all-quad mesh.
EstimateResult estimate_frame(const Mesh& sol, const EstimateOptions& opt = {},
                              const std::string& source = "");

/// The SHAPE mesh: sol's geometry and boundary groups, no input fields, plus CellFields
/// theta, rho, B, A1, A2, phi, model_A1, model_A2 and p (the DG degree, constant per cell). Curved cells become
/// their vertex view (straight-sided, same vertices and cells): the shape is a per-cell
/// constant, and size-solve's background mesh is straight.
Mesh make_shape_mesh(const Mesh& sol, const EstimateResult& r);

}  // namespace quadapt
