#include "sizing/size_field.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <queue>
#include <sstream>

#include "core/error.hpp"
#include "mesh/label.hpp"
#include "estimate/error_model.hpp"
#include "frame/frame.hpp"
#include "mesh/topology.hpp"

namespace quadapt {

namespace {

std::string num(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

const std::vector<double>* scalar_field(const Mesh& m, const std::string& name, bool required,
                                        const std::string& source) {
  const CellField* f = m.cell_field(name);
  if (!f) {
    if (!required) return nullptr;
    throw InputError(source, "no cell field \"" + name + "\" (expected the output of estimate-frame; fields present: " +
                                 m.field_list() + ")");
  }
  if (f->ncomp != 1 || f->num_cells() != m.num_cells())
    throw InputError(source, "cell field \"" + name + "\" must be scalar with one value per cell");
  for (double v : f->values)
    if (!std::isfinite(v)) throw InputError(source, "cell field \"" + name + "\" has non-finite values");
  return &f->values;
}

struct Bounds {
  double dmin, dmax;  // from hmax, hmin
};

// h_k <= g h_j for face neighbours: exact fixed point by processing cells in increasing h.
int apply_gradation(std::vector<double>& d, const std::vector<std::vector<int>>& nbrs, double g) {
  const int n = static_cast<int>(d.size());
  std::vector<double> h(n);
  for (int k = 0; k < n; ++k) h[k] = size_for_density(d[k]);
  std::vector<double> h0 = h;
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> pq;
  for (int k = 0; k < n; ++k) pq.emplace(h[k], k);
  while (!pq.empty()) {
    auto [hk, k] = pq.top();
    pq.pop();
    if (hk > h[k]) continue;  // stale
    for (int j : nbrs[k])
      if (h[j] > g * hk) {
        h[j] = g * hk;
        pq.emplace(h[j], j);
      }
  }
  int changed = 0;
  for (int k = 0; k < n; ++k) {
    if (h[k] < h0[k]) ++changed;
    d[k] = cell_density(h[k]);
  }
  return changed;
}

// Finds t in [lo, hi] with N(t) = C for a continuous monotone N (increasing if `increasing`).
// Returns the number of iterations; t is left in `t`.
int bisect(const std::function<double(double)>& N, double C, double lo, double hi, bool increasing,
           double& t) {
  int it = 0;
  for (; it < 300; ++it) {
    t = 0.5 * (lo + hi);
    const double v = N(t);
    if (std::abs(v - C) <= 1e-10 * C || hi - lo <= 1e-15 * std::max(1.0, std::abs(t))) break;
    if ((v < C) == increasing) lo = t; else hi = t;
  }
  return it + 1;
}

struct Common {
  ShapeData s;
  int n = 0;
  double area = 0;
  double hmin = 0, hmax = 0;
  Bounds b{};
  bool graded = false;
  std::vector<std::vector<int>> nbrs;  ///< face neighbours (gradation only)
};

Common setup(const Mesh& shape, const SizeOptions& opt, const std::string& source) {
  Common c;
  c.s = read_shape(shape, source);
  c.n = c.s.p + 1;
  for (double a : c.s.area) c.area += a;
  if (!(opt.complexity > 0) || !std::isfinite(opt.complexity))
    throw InputError("target complexity must be a positive number (got " + num(opt.complexity) + ")");
  if (!(opt.q >= 1)) throw InputError("q must be >= 1");
  if (!(opt.max_anisotropy >= 1)) throw InputError("maximum anisotropy must be >= 1");
  c.hmin = opt.hmin > 0 ? opt.hmin : 1e-6 * std::sqrt(c.area);
  c.hmax = opt.hmax > 0 ? opt.hmax : 0.125 * std::sqrt(c.area);
  if (!(c.hmin < c.hmax)) throw InputError("need hmin < hmax (got " + num(c.hmin) + ", " + num(c.hmax) + ")");
  c.b.dmin = cell_density(c.hmax);
  c.b.dmax = cell_density(c.hmin);
  if (opt.gradation != 0) {
    if (!(opt.gradation > 1)) throw InputError("gradation must be > 1 (or 0 = off), got " + num(opt.gradation));
    c.graded = true;
    Topology topo = build_topology(shape);
    c.nbrs.resize(shape.num_cells());
    for (int k = 0; k < shape.num_cells(); ++k) c.nbrs[k] = topo.neighbours(k);
  }
  return c;
}

// θ, ρ (clamped) and h from d.
void finish(SizeResult& r, const Common& c, const SizeOptions& opt) {
  const int nc = static_cast<int>(r.d.size());
  r.p = c.s.p;
  r.h.resize(nc);
  r.theta = c.s.theta;
  r.rho.resize(nc);
  r.hmin = c.hmin;
  r.hmax = c.hmax;
  for (int k = 0; k < nc; ++k) {
    r.h[k] = size_for_density(r.d[k]);
    // anisotropy: |log ρ| <= log of min(ρ_max, (hmax/h)^2, (h/hmin)^2), so that also the long
    // axis h1 <= hmax and the short axis h2 >= hmin (d, hence the complexity, is unchanged)
    const double cap = std::max(1.0, std::min({opt.max_anisotropy, std::pow(c.hmax / r.h[k], 2),
                                               std::pow(r.h[k] / c.hmin, 2)}));
    const double rho = c.s.rho[k];
    if (rho > cap * (1 + 1e-12) || rho < (1 - 1e-12) / cap) ++r.cells_anisotropy_capped;
    r.rho[k] = std::clamp(rho, 1 / cap, cap);
    if (r.d[k] <= c.b.dmin * (1 + 1e-12)) ++r.cells_at_hmax;
    if (r.d[k] >= c.b.dmax * (1 - 1e-12)) ++r.cells_at_hmin;
  }
  r.continuous_complexity = continuous_complexity(c.s.area, r.d, c.s.p);
}

}  // namespace

ShapeData read_shape(const Mesh& shape, const std::string& source) {
  ShapeData s;
  const int nc = shape.num_cells();
  if (nc == 0) throw InputError(source, "mesh has no cells");
  const auto* p = scalar_field(shape, "p", true, source);
  s.p = static_cast<int>(std::lround((*p)[0]));
  for (double v : *p)
    if (std::abs(v - s.p) > 1e-9 || s.p < 1)
      throw InputError(source, "field \"p\" must hold the same DG degree >= 1 in every cell");
  s.theta = *scalar_field(shape, "theta", true, source);
  s.rho = *scalar_field(shape, "rho", true, source);
  s.B = *scalar_field(shape, "B", true, source);
  // the model's bound coefficients when the SHAPE has them (estimate-frame's model_A1, model_A2),
  // else the thesis's A1, A2 (older SHAPE files: the same values with the thesis's model)
  const auto* m1 = scalar_field(shape, "model_A1", false, source);
  const auto* m2 = scalar_field(shape, "model_A2", false, source);
  const bool model = m1 && m2;
  if (auto* a1 = model ? m1 : scalar_field(shape, "A1", false, source)) s.A1 = *a1;
  if (auto* a2 = model ? m2 : scalar_field(shape, "A2", false, source)) s.A2 = *a2;
  if (s.A1.empty() != s.A2.empty()) s.A1.clear(), s.A2.clear();
  for (int k = 0; k < nc; ++k) {
    if (s.B[k] < 0) throw InputError(source, "field \"B\" is negative in " + cell_label(shape, k));
    if (!(s.rho[k] > 0)) throw InputError(source, "field \"rho\" must be positive (" + cell_label(shape, k) + ")");
    if (!s.A1.empty() && (s.A1[k] < 0 || s.A2[k] < 0))
      throw InputError(source, std::string(model ? "fields \"model_A1\", \"model_A2\"" : "fields \"A1\", \"A2\"") +
                                   " must be >= 0 (" + cell_label(shape, k) + ")");
  }
  s.area.resize(nc);
  for (int k = 0; k < nc; ++k) {
    s.area[k] = std::abs(cell_area(shape, k));
    if (!(s.area[k] > 0)) throw InputError(source, cell_label(shape, k) + " has zero area");
  }
  return s;
}

double continuous_complexity(const std::vector<double>& area, const std::vector<double>& d, int p) {
  double s = 0;
  for (size_t k = 0; k < d.size(); ++k) s += area[k] * d[k];
  return s * (p + 1) * (p + 1);
}

SizeResult solve_feature_size(const Mesh& shape, const SizeOptions& opt, const std::string& source) {
  Common c = setup(shape, opt, source);
  const int nc = shape.num_cells();
  const int n = c.n;
  const double q = opt.q;
  const double e = 2.0 / (q * n + 2);

  SizeResult r;
  r.target_complexity = opt.complexity;
  // error constants, re-evaluated for the anisotropy cap when A1, A2 are known
  r.B = c.s.B;
  if (!c.s.A1.empty())
    for (int k = 0; k < nc; ++k)
      r.B[k] = error_constant(c.s.A1[k], std::min(c.s.A1[k], effective_A2(c.s.A1[k], c.s.A2[k], n, opt.max_anisotropy)), n, q);
  double bmax = 0;
  for (int k = 0; k < nc; ++k) {
    // a finite but absurd model (A1 = 1e308) overflows here; it used to surface as "the largest
    // reachable complexity is 144 DOFs" (every other cell's B / bmax was 0): a CLI audit
    if (!std::isfinite(r.B[k]))
      throw InputError(source, cell_label(shape, k) + ": the error constant B overflows (" +
                                   (c.s.A1.empty() ? "B = " + num(c.s.B[k])
                                                   : "model A1 = " + num(c.s.A1[k]) + ", A2 = " + num(c.s.A2[k])) +
                                   "): the shape's error model is out of range");
    bmax = std::max(bmax, r.B[k]);
  }
  const bool uniform = !(bmax > 0);
  // b_k = B_k^e, normalised by bmax^e to keep K in range
  std::vector<double> b(nc);
  for (int k = 0; k < nc; ++k) b[k] = uniform ? 1.0 : std::pow(r.B[k] / bmax, e);

  auto density = [&](double K, std::vector<double>& d) {
    d.resize(nc);
    for (int k = 0; k < nc; ++k) d[k] = std::clamp(K * b[k], c.b.dmin, c.b.dmax);
    if (c.graded) r.cells_graded = apply_gradation(d, c.nbrs, opt.gradation);
  };
  std::vector<double> d;
  auto N = [&](double logK) {
    density(std::exp(logK), d);
    return continuous_complexity(c.s.area, d, c.s.p);
  };
  // admissible range
  const double Cmin = continuous_complexity(c.s.area, std::vector<double>(nc, c.b.dmin), c.s.p);
  std::vector<double> dsup(nc);
  for (int k = 0; k < nc; ++k) dsup[k] = b[k] > 0 ? c.b.dmax : c.b.dmin;
  if (c.graded) apply_gradation(dsup, c.nbrs, opt.gradation);
  const double Cmax = continuous_complexity(c.s.area, dsup, c.s.p);
  const double C = opt.complexity;
  if (C < Cmin * (1 - 1e-12))
    throw InputError(source, "target complexity " + num(C) + " is below the smallest this mesh can carry: " + num(Cmin) +
                                 " DOFs = (p+1)^2 x |domain| / (4 hmax^2) with hmax = " + num(c.hmax) +
                                 " (raise the complexity or --hmax)");
  if (C > Cmax * (1 + 1e-12))
    throw InputError(source, "target complexity " + num(C) + " exceeds the largest reachable with hmin = " +
                                 num(c.hmin) + ": " + num(Cmax) + " DOFs (lower the complexity or --hmin)");
  // bracket in log K around the unclamped solution K0
  double wsum = 0;
  for (int k = 0; k < nc; ++k) wsum += c.s.area[k] * b[k];
  const double K0 = C / (wsum * n * n);
  double lo = std::log(K0), hi = std::log(K0);
  for (int i = 0; i < 200 && N(lo) > C; ++i) lo -= 2;
  for (int i = 0; i < 200 && N(hi) < C; ++i) hi += 2;
  double t = lo;
  r.iterations = bisect(N, C, lo, hi, true, t);
  density(std::exp(t), d);
  r.d = d;
  // λ from K: d = K b = (q B / (2 λ n))^e with b = (B/bmax)^e  =>  λ = q bmax / (2 n K^(1/e))
  r.lambda = uniform ? 0.0 : q * bmax / (2 * n * std::pow(std::exp(t), 1 / e));
  finish(r, c, opt);
  return r;
}

double goal_alpha(double eta_k, double eta_ref, double eta_min, double eta_max, double r_max, double c_max) {
  if (eta_k > eta_ref) {
    const double den = std::log(eta_max) - std::log(eta_ref);
    const double xi = den > 0 ? (std::log(eta_k) - std::log(eta_ref)) / den : 0.0;
    return 1.0 / ((r_max - 1) * xi * xi + 1);
  }
  if (eta_k < eta_ref) {
    const double den = std::log(eta_min) - std::log(eta_ref);
    const double xi = den < 0 ? (std::log(eta_k) - std::log(eta_ref)) / den : 0.0;
    return (c_max - 1) * xi * xi + 1;
  }
  return 1.0;
}

SizeResult solve_goal_size(const Mesh& shape, const std::vector<double>& eta_in, const SizeOptions& opt,
                           const GoalOptions& gopt, const std::string& source) {
  Common c = setup(shape, opt, source);
  const int nc = shape.num_cells();
  if (static_cast<int>(eta_in.size()) != nc) throw InputError(source, "DWR indicator count does not match the cells");
  if (!(gopt.r_max >= 1) || !(gopt.c_max >= 1)) throw InputError("r_max and c_max must be >= 1");
  // adjoint writes |η_k| >= 0: a negative or non-finite value is a damaged or foreign file (a
  // negative one was taken as |η| and got the finest cells, with exit 0)
  double emax = 0;
  for (int k = 0; k < nc; ++k) {
    const double v = eta_in[k];
    if (!std::isfinite(v)) throw InputError(source, "field \"dwr\" is not finite in " + cell_label(shape, k));
    if (v < 0) throw InputError(source, "field \"dwr\" is negative in " + cell_label(shape, k));
    emax = std::max(emax, v);
  }
  if (!(emax > 0)) throw InputError(source, "DWR indicator is zero in every cell: nothing to adapt to");
  // |η|, floored at 1e-12 η_max so that the logarithms exist (stated in docs/size-solve.md)
  std::vector<double> eta(nc);
  double emin = emax;
  for (int k = 0; k < nc; ++k) {
    eta[k] = std::max(std::abs(eta_in[k]), 1e-12 * emax);
    emin = std::min(emin, eta[k]);
  }
  SizeResult r;
  r.target_complexity = opt.complexity;
  r.B = c.s.B;
  r.alpha.assign(nc, 1.0);
  std::vector<double> d(nc);
  auto build = [&](double alpha_uniform, double log_eta_ref) {
    for (int k = 0; k < nc; ++k) {
      r.alpha[k] = alpha_uniform > 0 ? alpha_uniform
                                     : goal_alpha(eta[k], std::exp(log_eta_ref), emin, emax, gopt.r_max, gopt.c_max);
      d[k] = std::clamp(1.0 / (r.alpha[k] * c.s.area[k]), c.b.dmin, c.b.dmax);
    }
    if (c.graded) r.cells_graded = apply_gradation(d, c.nbrs, opt.gradation);
    return continuous_complexity(c.s.area, d, c.s.p);
  };
  const double C = opt.complexity;
  const double n2 = static_cast<double>(c.n) * c.n;
  if (emax / emin < 1 + 1e-12) {
    // indistinguishable indicators: uniform area factor N/C, within [1/r_max, c_max]
    const double a = n2 * nc / C;
    if (a < 1 / gopt.r_max * (1 - 1e-12) || a > gopt.c_max * (1 + 1e-12))
      throw InputError(source, "uniform DWR: target complexity " + num(C) + " needs area factor " + num(a) +
                                   " outside [1/r_max, c_max] = [" + num(1 / gopt.r_max) + ", " + num(gopt.c_max) + "]");
    build(a, 0);
    r.eta_ref = emax;
  } else {
    const double lo = std::log(emin), hi = std::log(emax);
    const double Nmax = build(0, lo), Nmin = build(0, hi);
    if (C > Nmax * (1 + 1e-12) || C < Nmin * (1 - 1e-12))
      throw InputError(source, "target complexity " + num(C) + " is outside the range the DWR fit reaches with r_max = " +
                                   num(gopt.r_max) + ", c_max = " + num(gopt.c_max) + ": [" + num(Nmin) + ", " + num(Nmax) +
                                   "] DOFs (change the target, --r-max or --c-max)");
    double t = lo;
    r.iterations = bisect([&](double x) { return build(0, x); }, C, lo, hi, false, t);
    build(0, t);
    r.eta_ref = std::exp(t);
  }
  r.d = d;
  finish(r, c, opt);
  return r;
}

void check_same_cells(const Mesh& shape, const Mesh& dwr, const std::string& dwr_source) {
  if (shape.num_cells() != dwr.num_cells())
    throw InputError(dwr_source, "DWR file is on another mesh: " + std::to_string(dwr.num_cells()) +
                                     " cells, the SHAPE mesh has " + std::to_string(shape.num_cells()));
  double xmin = 1e300, xmax = -1e300, ymin = 1e300, ymax = -1e300;
  for (const auto& p : shape.nodes) {
    xmin = std::min(xmin, p.x()); xmax = std::max(xmax, p.x());
    ymin = std::min(ymin, p.y()); ymax = std::max(ymax, p.y());
  }
  const double tol = 1e-8 * std::max(xmax - xmin, ymax - ymin);
  for (int k = 0; k < shape.num_cells(); ++k)
    if ((cell_centroid(shape, k) - cell_centroid(dwr, k)).norm() > tol)
      throw InputError(dwr_source, "DWR file is on another mesh: cell " + number_text(k) +
                                       " has a different centroid than in the SHAPE mesh");
}

nlohmann::json to_json(const SizeResult& r) {
  auto lo = [](const std::vector<double>& v) { return v.empty() ? 0.0 : *std::min_element(v.begin(), v.end()); };
  auto hi = [](const std::vector<double>& v) { return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end()); };
  nlohmann::json j;
  j["p"] = r.p;
  j["target_complexity"] = r.target_complexity;
  j["continuous_complexity"] = r.continuous_complexity;
  j["expected_cells"] = cells_for_complexity(r.continuous_complexity, r.p);
  if (r.alpha.empty()) {
    j["lambda"] = r.lambda;
  } else {
    j["eta_ref"] = r.eta_ref;
    j["alpha_min"] = lo(r.alpha);
    j["alpha_max"] = hi(r.alpha);
  }
  j["h_min"] = lo(r.h);
  j["h_max"] = hi(r.h);
  j["rho_max"] = hi(r.rho);
  j["hmin_bound"] = r.hmin;
  j["hmax_bound"] = r.hmax;
  j["cells_at_hmin"] = r.cells_at_hmin;
  j["cells_at_hmax"] = r.cells_at_hmax;
  j["cells_anisotropy_capped"] = r.cells_anisotropy_capped;
  j["cells_graded"] = r.cells_graded;
  j["bisection_iterations"] = r.iterations;
  return j;
}

}  // namespace quadapt
