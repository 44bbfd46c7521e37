#include "estimate/estimate_frame.hpp"

#include <algorithm>
#include <limits>
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "core/format.hpp"
#include "estimate/directional.hpp"
#include "estimate/error_model.hpp"
#include "estimate/polynomial_model.hpp"
#include "estimate/reconstruct.hpp"
#include "fem/basis.hpp"
#include "mesh/label.hpp"
#include "mesh/topology.hpp"

namespace quadapt {

std::vector<std::vector<int>> reconstruction_patches(const Mesh& m, PatchKind kind) {
  const int nc = m.num_cells();
  Topology topo = build_topology(m);
  std::vector<std::vector<int>> node_cells;
  if (kind == PatchKind::Vertex) {
    node_cells.resize(m.num_nodes());
    for (int c = 0; c < nc; ++c)
      for (int k = 0; k < m.cells[c].nv; ++k) node_cells[m.cells[c].v[k]].push_back(c);
  }
  std::vector<std::vector<int>> patches(nc);
  for (int c = 0; c < nc; ++c) {
    std::vector<int> p = topo.neighbours(c);
    if (kind == PatchKind::Vertex)
      for (int k = 0; k < m.cells[c].nv; ++k)
        for (int o : node_cells[m.cells[c].v[k]]) p.push_back(o);
    std::sort(p.begin(), p.end());
    p.erase(std::unique(p.begin(), p.end()), p.end());
    p.erase(std::remove(p.begin(), p.end(), c), p.end());
    p.insert(p.begin(), c);
    patches[c] = std::move(p);
  }
  return patches;
}

namespace {
// The observed-error floor: ratio_K = misfit_K / (B_K |K|^((qn+2)/2)) is about constant (κ, its
// median) where the Taylor model holds; where it exceeds τκ, B_K (and model_A1 A2, so that
// size-solve's re-evaluation at its cap keeps the raise) is multiplied by ratio_K / (τκ), at most
// kMaxRaise: a singular cell misfits at every size, and the model, whose rate h^(q(p+1)+2) it does
// not follow, would keep investing in it (uncapped, an L-shape loop at p = 3 coarsened the rest
// of the domain 3x at its step 7 and its error rose 16x; docs/estimate-frame.md).
constexpr double kMaxRaise = 64;
// area: |cell area| per cell; noise: per cell, the misfit that rounding alone gives.
// A cell whose misfit is at that level tells nothing about the model (u_h may be the polynomial
// exactly): it takes no part in κ and is never raised. Without this, a field that the model
// describes exactly had its B raised up to 64x on the cells whose rounding happened to be above
// the median rounding (a review: 15-19 of 64 cells; B no longer invariant under rotation).
void raise_by_misfit(const std::vector<double>& area, const std::vector<double>& noise, const EstimateOptions& opt,
                     EstimateResult& r) {
  const int nc = static_cast<int>(r.B.size());
  const int n = r.p + 1;
  std::vector<double> ratio(nc, 0), positive;
  for (int c = 0; c < nc; ++c) {
    if (!(r.B[c] > 0) || !(r.misfit[c] > noise[c])) continue;
    const double model = r.B[c] * std::pow(area[c], (opt.q * n + 2) / 2);
    ratio[c] = r.misfit[c] / model;
    positive.push_back(ratio[c]);
  }
  if (positive.empty()) return;
  std::nth_element(positive.begin(), positive.begin() + positive.size() / 2, positive.end());
  const double kappa = positive[positive.size() / 2];
  r.misfit_ratio_median = kappa;
  if (!(kappa > 0)) return;
  for (int c = 0; c < nc; ++c) {
    const double excess = std::min(kMaxRaise, ratio[c] / (opt.observed_floor * kappa));
    if (!(r.B[c] > 0) || !(r.misfit[c] > noise[c]) || !(excess > 1)) continue;
    r.B[c] *= excess;
    // B ∝ (A1 A2)^(q/2): both coefficients by excess^(1/q) keep ρ and give B · excess
    const double g = std::pow(excess, 1 / opt.q);
    r.model_A1[c] *= g;
    r.model_A2[c] *= g;
    ++r.cells_raised;
  }
}
// What "zero" means for a difference of values of size U fitted by least squares on a patch:
// about ε U times the fit's conditioning (kRoundingFactor, generous: the patches' Vandermonde
// systems in scaled coordinates). Used for the noise floor and the observed-error floor.
constexpr double kRoundingFactor = 1e3;
}  // namespace

EstimateResult estimate_frame(const Mesh& sol, const EstimateOptions& opt, const std::string& source) {
  // the mesh first: a triangle mesh has no DG field either, and "no field" would hide the cause
  if (!sol.all_quads())
    throw InputError(source, "the DG solution mesh must be all-quad (it has triangles: dgsolve solves on quads)");
  const CellNodeField* f = sol.cell_node_field(opt.field);
  if (!f)
    throw InputError(source, "no DG solution field \"" + opt.field +
                                 "\" ($ElementNodeData with a GLL interpolation scheme); "
                                 "expected the output of dgsolve");
  if (f->degree < 0 || f->ncomp != 1)
    throw InputError(source, "field \"" + opt.field + "\" is not a scalar DG field of degree p "
                             "(no GLL interpolation scheme)");
  const int p = f->degree;
  if (f->per_cell != (p + 1) * (p + 1))
    throw InputError(source, "field \"" + opt.field + "\" has " + std::to_string(f->per_cell) +
                                 " values per cell, expected (p+1)^2 = " + std::to_string((p + 1) * (p + 1)));
  if (f->num_cells() != sol.num_cells())
    throw InputError(source, "field \"" + opt.field + "\" does not match the cell count");
  if (sol.num_cells() == 0) throw InputError(source, "the mesh has no cells");
  if (!(opt.q >= 1)) throw InputError("q must be >= 1");
  if (!(opt.max_anisotropy >= 1)) throw InputError("max anisotropy must be >= 1");
  if (!(opt.observed_floor == 0 || opt.observed_floor >= 1))
    throw InputError("the observed-error floor must be 0 (off) or >= 1");
  for (double v : f->values)
    if (!std::isfinite(v)) throw InputError(source, "field \"" + opt.field + "\" has non-finite values");

  const int n = p + 1;
  const int nc = sol.num_cells();
  const std::vector<std::vector<int>> patches = reconstruction_patches(sol, opt.patch);
  PatchReconstructor rec(sol, f->values, p, n);
  std::vector<double> area(nc);
  for (int c = 0; c < nc; ++c) area[c] = std::abs(cell_area(sol, c));

  EstimateResult r;
  r.p = p;
  r.A1.assign(nc, 0); r.A2.assign(nc, 0); r.phi.assign(nc, 0);
  r.theta.assign(nc, 0); r.rho.assign(nc, 1); r.B.assign(nc, 0);
  r.model_A1.assign(nc, 0); r.model_A2.assign(nc, 0);

  bool failed = false;
  std::string what;
  std::vector<std::vector<double>> tops(nc);  // P of every cell (polynomial model)
  r.misfit.assign(nc, 0);
  const std::vector<double> gll = LagrangeBasis1D(p).nodes();  // the DG field's nodes
#pragma omp parallel for schedule(static)
  for (int c = 0; c < nc; ++c) {
    try {
      PatchPolynomial poly = rec.reconstruct(c, patches[c]);
      tops[c] = poly.top_homogeneous();
      // the misfit of ũ to u_h: mean |ũ − u_h|^q over the cell's GLL nodes, times its area
      double s = 0;
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const double d = poly.eval(map_to_physical(sol, c, gll[i], gll[j])) -
                           f->values[static_cast<size_t>(c) * n * n + i + n * j];
          s += opt.q == 2 ? d * d : std::pow(std::abs(d), opt.q);
        }
      r.misfit[c] = s / (n * n) * area[c];
      DirectionalExtrema d = directional_extrema(tops[c]);
      r.A1[c] = d.A1;
      r.A2[c] = d.A2;
      r.phi[c] = d.phi;
    } catch (const std::exception& e) {
#pragma omp critical
      {
        failed = true;
        what = e.what();
      }
    }
  }
  if (failed) throw NumericalError(source.empty() ? what : source + ": " + what);

  // The size of u that each cell's fit saw: max |u_h| over its patch's nodes (the rounding scale).
  std::vector<double> cell_umax(nc, 0), patch_umax(nc, 0);
  const size_t per_cell = static_cast<size_t>(n) * n;
  for (int c = 0; c < nc; ++c)
    for (size_t k = 0; k < per_cell; ++k) cell_umax[c] = std::max(cell_umax[c], std::abs(f->values[c * per_cell + k]));
  for (int c = 0; c < nc; ++c)
    for (int o : patches[c]) patch_umax[c] = std::max(patch_umax[c], cell_umax[o]);
  // ... and how much a stretched cell amplifies it: a degree-n derivative across a cell of h_long x
  // h_short carries ε U / h_short^n, which is ε U (h_long / h_short)^(n/2) on the scale A1 h_k^n
  // (h_k = sqrt(area)); h_long / h_short ~ longest edge^2 / area. Without it, u = 1000 + x on
  // cells of aspect 1000 got noise directions with ρ up to 3000 (a review).
  std::vector<double> rounding(nc);
  for (int c = 0; c < nc; ++c) {
    double longest2 = 0;
    const Cell& cell = sol.cells[c];
    for (int k = 0; k < cell.nv; ++k)
      longest2 = std::max(longest2, (sol.nodes[cell.v[(k + 1) % cell.nv]] - sol.nodes[cell.v[k]]).squaredNorm());
    const double stretch = std::max(1.0, longest2 / area[c]);
    rounding[c] = kRoundingFactor * std::numeric_limits<double>::epsilon() * patch_umax[c] * std::pow(stretch, 0.5 * n);
  }
  // Noise floor: a cell whose degree-(p+1) term changes u over the cell (A1 h_k^n) by at most
  // direction_floor · (max u − min u) / 2 — half the oscillation, max|u − c| about the range's
  // centre c: max|u| for a field symmetric about 0, and u + const gives the same shape (with max|u|
  // an offset of 1e3 zeroed 252 more cells of a Gaussian: a review) — or by no more than
  // the rounding of its fit (`rounding`, above), or whose A1 is below
  // direction_floor · max A1, has no meaningful derivative: A1 = A2 = 0, phi = 0, B = 0,
  // isotropic θ = 0, ρ = 1.
  double amax = 0;
  for (double a : r.A1) amax = std::max(amax, a);
  const auto [umin_it, umax_it] = std::minmax_element(f->values.begin(), f->values.end());
  const double half_oscillation = f->values.empty() ? 0.0 : 0.5 * (*umax_it - *umin_it);
#pragma omp parallel for schedule(static)
  for (int c = 0; c < nc; ++c) {
    const double hk = std::sqrt(area[c]);
    const double zero = std::max(opt.direction_floor * half_oscillation, rounding[c]);
    if (r.A1[c] * std::pow(hk, n) <= zero || r.A1[c] <= opt.direction_floor * amax) {
      // phi too: the direction of a noise term would differ between a field and its mirror image
      r.A1[c] = r.A2[c] = r.phi[c] = 0;
      continue;
    }
    r.model_A1[c] = r.A1[c];
    r.model_A2[c] = r.A2[c];
    if (opt.model == ErrorModel::Polynomial) {
      // the thesis's orientation (the short axis along A1), the stretch and B of the whole term
      const PolynomialShape ps = polynomial_stretch(tops[c], opt.q, opt.max_anisotropy, r.phi[c] - 0.5 * M_PI);
      r.model_A1[c] = ps.A1;
      r.model_A2[c] = ps.A2;
    }
    FrameShape s = optimal_shape(r.model_A1[c], r.model_A2[c], r.phi[c], n, opt.q, opt.max_anisotropy);
    r.B[c] = s.B;
    r.theta[c] = s.theta;
    r.rho[c] = s.rho;
  }
  // a field whose derivatives overflow the model (u = 1e300 x^3): named here with the input and
  // the cause, not later as an output that refuses a non-finite field (a review)
  for (int c = 0; c < nc; ++c)
    if (!std::isfinite(r.B[c]) || !std::isfinite(r.A1[c]) || !std::isfinite(r.model_A1[c]))
      throw NumericalError((source.empty() ? std::string() : source + ": ") + "the error model overflows in " +
                           cell_label(sol, c) + " (A1 = " + sci(r.A1[c]) + ", B = " + sci(r.B[c]) +
                           "): the field's degree-" + std::to_string(n) + " derivatives are beyond double precision; "
                           "scale u down (the frame does not depend on u's scale)");
  if (opt.observed_floor > 0) {
    // the misfit m_K = |K| mean |ũ − u_h|^q that rounding alone gives
    std::vector<double> noise(nc);
    for (int c = 0; c < nc; ++c) noise[c] = std::pow(rounding[c], opt.q) * area[c];
    raise_by_misfit(area, noise, opt, r);
  }
  return r;
}

Mesh make_shape_mesh(const Mesh& sol, const EstimateResult& r) {
  Mesh m = sol;
  m.clear_fields();
  m.curved = CurvedGeometry{};  // the vertex view: per-cell constants on a background mesh
  auto scalar = [&](const std::string& name, const std::vector<double>& v) {
    CellField f;
    f.name = name;
    f.ncomp = 1;
    f.values = v;
    m.set_field(std::move(f));
  };
  scalar("theta", r.theta);
  scalar("rho", r.rho);
  scalar("B", r.B);
  scalar("A1", r.A1);
  scalar("A2", r.A2);
  scalar("phi", r.phi);
  scalar("model_A1", r.model_A1);
  scalar("model_A2", r.model_A2);
  scalar("p", std::vector<double>(r.A1.size(), static_cast<double>(r.p)));
  return m;
}

}  // namespace quadapt
