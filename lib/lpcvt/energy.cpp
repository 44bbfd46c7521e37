#include "lpcvt/energy.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "lpcvt/quadrature.hpp"

namespace quadapt::lpcvt {

namespace {

inline double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

/// f = |F|^p and g = df/dF.
inline void power(double F, double p, double& f, double& g) {
  if (p == 6) {
    double F2 = F * F, F4 = F2 * F2;
    f = F4 * F2;
    g = 6 * F4 * F;
  } else if (p == 2) {
    f = F * F;
    g = 2 * F;
  } else if (p == 4) {
    double F2 = F * F;
    f = F2 * F2;
    g = 4 * F2 * F;
  } else {
    double a = std::abs(F);
    if (a == 0) {
      f = 0;
      g = 0;
      return;
    }
    double am = std::pow(a, p - 1);
    f = am * a;
    g = p * am * (F < 0 ? -1 : 1);
  }
}

int g_min_parallel_sites = 2000;

struct Contribution {
  int site;
  Vec2 g;
};

/// Integrates one piece: returns its energy, appends gradient contributions when `out` != null.
double integrate_piece(const RvdPiece& pc, const Background& bg, const std::vector<Vec2>& x,
                       double p, const TriangleRule& rule, std::vector<Contribution>* out,
                       std::vector<Vec2>& G) {
  const int m = static_cast<int>(pc.v.size());
  const Vec2& xi = x[pc.site];
  const bool analytic = bg.is_analytic();
  Mat2 M = bg.cell(pc.cell).M, d0 = Mat2::Zero(), d1 = Mat2::Zero();
  double E = 0;
  Vec2 gx = Vec2::Zero();
  if (out) G.assign(m, Vec2::Zero());
  const Vec2& A = pc.v[0];
  for (int t = 1; t + 1 < m; ++t) {
    const Vec2 &B = pc.v[t], &C = pc.v[t + 1];
    const double J = cross(B - A, C - A);
    if (J == 0 && !out) continue;
    double Et = 0;
    Vec2 gxt = Vec2::Zero(), GA = Vec2::Zero(), GB = Vec2::Zero(), GC = Vec2::Zero();
    for (int q = 0; q < rule.size(); ++q) {
      const auto& l = rule.bary[q];
      const Vec2 y = l[0] * A + l[1] * B + l[2] * C;
      if (analytic) bg.metric_derivs(pc.cell, y, M, d0, d1);
      const Vec2 d = y - xi;
      const Vec2 F = M * d;
      double f0, g0, f1, g1;
      power(F.x(), p, f0, g0);
      power(F.y(), p, f1, g1);
      const double w = rule.w[q];
      Et += w * (f0 + f1);
      if (!out) continue;
      const Vec2 g(g0, g1);
      Vec2 gy = M.transpose() * g;  // d f / d y through (y - x)
      gxt -= w * gy;
      if (analytic) gy += Vec2(g.dot(d0 * d), g.dot(d1 * d));
      GA += (w * l[0]) * gy;
      GB += (w * l[1]) * gy;
      GC += (w * l[2]) * gy;
    }
    const double area = 0.5 * J;
    E += area * Et;
    if (!out) continue;
    gx += area * gxt;
    // d area / d vertex
    const Vec2 dJB(C.y() - A.y(), -(C.x() - A.x()));
    const Vec2 dJC(-(B.y() - A.y()), B.x() - A.x());
    G[0] += area * GA - 0.5 * Et * (dJB + dJC);
    G[t] += area * GB + 0.5 * Et * dJB;
    G[t + 1] += area * GC + 0.5 * Et * dJC;
  }
  if (!out) return E;
  out->push_back({pc.site, gx});
  // Chain rule through the vertices: each is the intersection of the lines of its two edges.
  const IntegrationCell& Q = bg.cell(pc.cell);
  for (int k = 0; k < m; ++k) {
    const int la = pc.label[k == 0 ? m - 1 : k - 1], lb = pc.label[k];
    if (la < 0 && lb < 0) continue;
    if (G[k].x() == 0 && G[k].y() == 0) continue;
    const Vec2& c = pc.v[k];
    auto normal = [&](int lab) -> Vec2 {
      if (lab >= 0) return x[lab] - xi;
      int e = -1 - lab;
      Vec2 t = Q.v[(e + 1) % Q.nv] - Q.v[e];
      return Vec2(t.y(), -t.x());
    };
    Mat2 Am;
    Am.row(0) = normal(la).transpose();
    Am.row(1) = normal(lb).transpose();
    const double det = Am.determinant();
    if (!(std::abs(det) > 1e-300)) continue;
    // lambda = -A^-T G
    Mat2 AinvT;
    AinvT << Am(1, 1), -Am(1, 0), -Am(0, 1), Am(0, 0);
    AinvT /= det;
    const Vec2 lam = -(AinvT * G[k]);
    const int labs[2] = {la, lb};
    for (int r = 0; r < 2; ++r) {
      const int j = labs[r];
      if (j < 0) continue;
      out->push_back({pc.site, lam[r] * (xi - c)});
      out->push_back({j, lam[r] * (c - x[j])});
    }
  }
  return E;
}

}  // namespace

EnergyResult lp_energy(const RestrictedVoronoi& rvd, const Background& bg, double p,
                       bool gradient) {
  const std::vector<Vec2>& x = rvd.sites();
  const int nq = bg.num_cells();
  const TriangleRule& rule = rule_for_exponent(p);
  std::vector<double> eq(nq, 0.0);
  std::vector<std::vector<Contribution>> contrib(gradient ? nq : 0);
  std::vector<long> npieces(nq, 0);
  // Parallel only when there is enough work: small problems lose more to thread start-up and
  // (on a loaded machine) to spinning threads than they gain.
  const bool parallel = static_cast<int>(x.size()) >= g_min_parallel_sites && nq >= 8;
#pragma omp parallel if (parallel)
  {
    RvdWorkspace ws;
    std::vector<RvdPiece> pcs;
    std::vector<Vec2> G;
#pragma omp for schedule(dynamic, 8)
    for (int q = 0; q < nq; ++q) {
      rvd.pieces(q, pcs, ws);
      npieces[q] = static_cast<long>(pcs.size());
      double e = 0;
      for (const RvdPiece& pc : pcs)
        e += integrate_piece(pc, bg, x, p, rule, gradient ? &contrib[q] : nullptr, G);
      eq[q] = e;
    }
  }
  EnergyResult r;
  for (int q = 0; q < nq; ++q) {
    r.energy += eq[q];
    r.pieces += npieces[q];
  }
  if (gradient) {
    r.grad.assign(x.size(), Vec2::Zero());
    for (int q = 0; q < nq; ++q)
      for (const Contribution& c : contrib[q]) r.grad[c.site] += c.g;
  }
  return r;
}

void set_min_parallel_sites(int n) { g_min_parallel_sites = std::max(0, n); }

EnergyResult lp_energy(const Background& bg, const std::vector<Vec2>& sites, double p,
                       bool gradient) {
  RestrictedVoronoi rvd(bg, sites);
  return lp_energy(rvd, bg, p, gradient);
}

double piece_energy(const RvdPiece& piece, const Background& bg, const Vec2& x_site, double p) {
  std::vector<Vec2> x(static_cast<size_t>(piece.site) + 1, x_site);
  std::vector<Vec2> G;
  return integrate_piece(piece, bg, x, p, rule_for_exponent(p), nullptr, G);
}

}  // namespace quadapt::lpcvt
