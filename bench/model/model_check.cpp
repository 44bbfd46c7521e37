// model_check — does the continuous error model predict the error of an adapted mesh?
// (docs/estimate-frame.md, "Does the model predict the error?"). Not a tool: a measurement
// program for engineers, built by bench/model/Makefile against libquadapt.
//
//   model_check SOL.msh CASE.json [--cap RHO]        per-cell comparison on a dgsolve output
//   model_check --ideal CASE.json P C [--cap RHO] [--grid G]
//                                                     model-optimal L2 error at complexity C
//
// Per-cell comparison (cell k, n = p + 1, area |k|, exact solution u from CASE):
//   DG      ∫_k (u - u_h)²                        the solver's error (u_h = field "u" of SOL)
//   interp  ∫_k (u - I_p u)²                      I_p = degree-p GLL interpolation on k
//   taylor  ∫_k (T - I_p T)²                      T = exact degree-n Taylor term at the
//                                                 centroid (eq. 5.6): the local model on the
//                                                 cell as it is (size, shape, orientation)
//   optimal B_k |k|^(n+1)                         the model if k had the optimal shape at its
//                                                 area (eq. 5.15 with q = 2, d = 1/|k|), B from
//                                                 the exact derivatives (estimate/error_model)
// grouped by quintiles of the exact A1 (cells sorted by feature strength), with the cell's
// aspect ratio (longer/shorter chord through its centre), the requested ρ (exact, capped at
// --cap, default 25 = size-solve's default) and the angle between the longer chord and θ.
// Also: estimate-frame's reconstruction (A1, A2, B, φ from SOL) against the exact values on
// cells with A1 ≥ 10% of the maximum.
//
// --ideal: for aligned Q_p rectangles with the exact (A1, A2) and ρ ≤ cap, the GLL
// interpolation error of T is |k| c_ω (|k|/4)^n min_r (A1² r^n + A2² r^-n), c_ω = mean of
// ω² on [-1, 1], ω = Π (s - s_i) over the GLL nodes (the mixed monomials of T lie in Q_p).
// With b(x) that constant per |k|^(n+1), the optimum over densities of ∫ b d^-n subject to
// ∫ d = N cells is E = (∫ b^(1/(n+1)))^(n+1) N^-n (the same exponent as eq. 5.21 with
// q = 2): L2 = sqrt(E) at N = C/(p+1)², integrated on a G × G midpoint grid of the unit square.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numeric>
#include <string>
#include <vector>

#include "case/case.hpp"
#include "case/expression.hpp"
#include "fem/basis.hpp"
#include "estimate/directional.hpp"
#include "estimate/error_model.hpp"
#include "estimate/estimate_frame.hpp"
#include "io/msh.hpp"

using namespace quadapt;

namespace {

// Taylor coefficients a_i of the degree-n term, Σ a_i y_x^i y_y^(n-i) (directional.hpp).
struct TaylorTerm {
  int n;
  ExprProgram prog;
  TaylorTerm(const Expr& u, int n_) : n(n_) {
    std::vector<Expr> outs;
    for (int i = 0; i <= n; ++i) {
      Expr e = u;
      for (int a = 0; a < i; ++a) e = differentiate(e, 0);
      for (int b = 0; b < n - i; ++b) e = differentiate(e, 1);
      outs.push_back(e);
    }
    prog = ExprProgram(outs);
  }
  std::vector<double> at(double x, double y) const {
    std::vector<double> d = prog.eval(x, y);
    for (int i = 0; i <= n; ++i) d[i] /= std::tgamma(i + 1.0) * std::tgamma(n - i + 1.0);
    return d;
  }
};

double quantile(std::vector<double> v, double t) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(t * v.size()))];
}

double sum(const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0); }

int ideal(const Case& cs, int p, double C, double cap, int G) {
  const int n = p + 1;
  TaylorTerm T(cs.exact, n);
  LagrangeBasis1D lb(p);
  Rule1D g = gauss_legendre(2 * n + 2);
  double cw = 0;
  for (size_t k = 0; k < g.x.size(); ++k) {
    double w = 1;
    for (double s : lb.nodes()) w *= g.x[k] - s;
    cw += 0.5 * g.w[k] * w * w;
  }
  double I = 0;
  for (int j = 0; j < G; ++j)
    for (int i = 0; i < G; ++i) {
      DirectionalExtrema de = directional_extrema(T.at((i + 0.5) / G, (j + 0.5) / G));
      const double A1 = de.A1, A2 = de.A2;
      double r = (A1 > 0 && A2 > 0) ? std::pow(A2 / A1, 1.0 / n) : 1 / cap;  // a_along-ξ1 / a_across
      r = std::clamp(r, 1 / cap, cap);
      const double b = cw * std::pow(4.0, -n) * (A1 * A1 * std::pow(r, n) + A2 * A2 * std::pow(r, -n));
      I += std::pow(b, 1.0 / (n + 1)) / (static_cast<double>(G) * G);
    }
  const double N = C / (n * n);
  std::printf("ideal aligned Q%d rectangles, rho <= %g, C = %.4g DOFs (%.4g cells): L2 = %.3e  (c_omega = %.5f)\n",
              p, cap, C, N, std::sqrt(std::pow(I, n + 1) * std::pow(N, -n)), cw);
  return 0;
}

int compare(const std::string& solpath, const Case& cs, double cap) {
  Mesh sol = read_msh(solpath);
  const CellNodeField* f = sol.cell_node_field("u");
  if (!f || f->degree < 1) {
    std::fprintf(stderr, "%s: no DG field u\n", solpath.c_str());
    return 2;
  }
  const int p = f->degree, n = p + 1, nc = sol.num_cells();
  TaylorTerm T(cs.exact, n);
  ExprProgram uprog(std::vector<Expr>{cs.exact});
  const EstimateResult rec = estimate_frame(sol, EstimateOptions{}, solpath);
  LagrangeBasis1D basis(p);
  const auto& nodes = basis.nodes();
  Rule1D g = gauss_legendre(p + 6);
  std::vector<double> dg(nc), in(nc), ta(nc), op(nc), A1(nc), A2(nc), B(nc), phi(nc), aspect(nc), mis(nc), rq(nc), area(nc);
#pragma omp parallel for schedule(static)
  for (int c = 0; c < nc; ++c) {
    const Vec2 xc = cell_centroid(sol, c);
    const std::vector<double> a = T.at(xc.x(), xc.y());
    const DirectionalExtrema de = directional_extrema(a);
    const FrameShape s = optimal_shape(de.A1, de.A2, de.phi, n, 2, 1e6);
    A1[c] = de.A1; A2[c] = de.A2; phi[c] = de.phi; B[c] = s.B;
    auto taylor = [&](const Vec2& x) {
      double v = 0;
      for (int i = 0; i <= n; ++i) v += a[i] * std::pow(x.x() - xc.x(), i) * std::pow(x.y() - xc.y(), n - i);
      return v;
    };
    std::vector<double> uI((p + 1) * (p + 1)), tI((p + 1) * (p + 1)), scratch(uprog.scratch_size());
    for (int j = 0; j <= p; ++j)
      for (int i = 0; i <= p; ++i) {
        const Vec2 x = map_to_physical(sol, c, nodes[i], nodes[j]);
        uprog.eval(x.x(), x.y(), &uI[i + (p + 1) * j], scratch.data());
        tI[i + (p + 1) * j] = taylor(x);
      }
    double se = 0, si = 0, st = 0;
    for (size_t qj = 0; qj < g.x.size(); ++qj)
      for (size_t qi = 0; qi < g.x.size(); ++qi) {
        const Eigen::Matrix2d J = map_jacobian(sol, c, g.x[qi], g.x[qj]);
        const double w = g.w[qi] * g.w[qj] * std::abs(J(0, 0) * J(1, 1) - J(0, 1) * J(1, 0));
        const Vec2 x = map_to_physical(sol, c, g.x[qi], g.x[qj]);
        double u;
        uprog.eval(x.x(), x.y(), &u, scratch.data());
        const double eh = u - eval_tensor(basis, f->cell(c), g.x[qi], g.x[qj]);
        const double ei = u - eval_tensor(basis, uI.data(), g.x[qi], g.x[qj]);
        const double et = taylor(x) - eval_tensor(basis, tI.data(), g.x[qi], g.x[qj]);
        se += w * eh * eh; si += w * ei * ei; st += w * et * et;
      }
    area[c] = std::abs(cell_area(sol, c));
    dg[c] = se; in[c] = si; ta[c] = st;
    op[c] = B[c] * std::pow(area[c], n + 1.0);
    const Eigen::Matrix2d J = map_jacobian(sol, c, 0, 0);
    Eigen::Vector2d c1 = J.col(0), c2 = J.col(1);
    if (c1.norm() < c2.norm()) std::swap(c1, c2);
    aspect[c] = c1.norm() / c2.norm();
    double d = std::fmod(std::abs(std::atan2(c1.y(), c1.x()) - s.theta), M_PI);
    mis[c] = std::min(d, M_PI - d) * 180 / M_PI;
    rq[c] = std::min(s.rho, cap);
  }
  std::printf("%s: %d cells, p = %d\n", solpath.c_str(), nc, p);
  std::printf("  L2: DG %.4e  interp %.4e  taylor %.4e  optimal-shape model %.4e   DG/interp (squared) %.3f\n",
              std::sqrt(sum(dg)), std::sqrt(sum(in)), std::sqrt(sum(ta)), std::sqrt(sum(op)), sum(dg) / sum(in));
  const double amax = *std::max_element(A1.begin(), A1.end());
  std::vector<double> r1, r2, rB, dphi;
  for (int c = 0; c < nc; ++c)
    if (A1[c] >= 0.1 * amax && A2[c] > 0 && B[c] > 0) {
      r1.push_back(rec.A1[c] / A1[c]);
      r2.push_back(rec.A2[c] / A2[c]);
      rB.push_back(rec.B[c] / B[c]);
      const double d = std::abs(rec.phi[c] - phi[c]);
      dphi.push_back(std::min(d, M_PI - d) * 180 / M_PI);
    }
  std::printf("  reconstruction on %zu cells with A1 >= 10%% max (q10 / median / q90): A1 %.3f %.3f %.3f  A2 %.3f %.3f %.3f  "
              "B %.3f %.3f %.3f  |dphi| %.2f %.2f %.2f deg\n", r1.size(), quantile(r1, .1), quantile(r1, .5), quantile(r1, .9),
              quantile(r2, .1), quantile(r2, .5), quantile(r2, .9), quantile(rB, .1), quantile(rB, .5), quantile(rB, .9),
              quantile(dphi, .1), quantile(dphi, .5), quantile(dphi, .9));
  std::vector<int> order(nc);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return A1[a] < A1[b]; });
  std::printf("  quintile of exact A1 | share of squared error: DG interp taylor optimal | taylor/interp | area | aspect med (q90) | requested rho med | misalignment med (q90) deg\n");
  for (int b = 0; b < 5; ++b) {
    double sd = 0, si = 0, st = 0, so = 0, sa = 0;
    std::vector<double> va, vr, vm;
    for (int i = b * nc / 5; i < (b + 1) * nc / 5; ++i) {
      const int c = order[i];
      sd += dg[c]; si += in[c]; st += ta[c]; so += op[c]; sa += area[c];
      va.push_back(aspect[c]); vr.push_back(rq[c]); vm.push_back(mis[c]);
    }
    std::printf("  %d | %.3f %.3f %.3f %.3f | %.2f | %.3f | %.2f (%.2f) | %.2f | %.1f (%.1f)\n", b, sd / sum(dg), si / sum(in),
                st / sum(ta), so / sum(op), si / st, sa, quantile(va, .5), quantile(va, .9), quantile(vr, .5), quantile(vm, .5),
                quantile(vm, .9));
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    std::vector<std::string> a(argv + 1, argv + argc);
    double cap = 25;
    int grid = 400;
    for (size_t i = 0; i + 1 < a.size(); ++i) {
      if (a[i] == "--cap") { cap = std::atof(a[i + 1].c_str()); a.erase(a.begin() + i, a.begin() + i + 2); --i; }
      else if (a[i] == "--grid") { grid = std::atoi(a[i + 1].c_str()); a.erase(a.begin() + i, a.begin() + i + 2); --i; }
    }
    if (a.size() == 4 && a[0] == "--ideal") return ideal(load_case(a[1]), std::atoi(a[2].c_str()), std::atof(a[3].c_str()), cap, grid);
    if (a.size() == 2) return compare(a[0], load_case(a[1]), cap);
    std::fprintf(stderr, "usage: model_check SOL.msh CASE.json [--cap RHO]\n"
                         "       model_check --ideal CASE.json P C [--cap RHO] [--grid G]\n");
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "model_check: %s\n", e.what());
    return 2;
  }
}
