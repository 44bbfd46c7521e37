#include "lpcvt/metric_filter.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <queue>
#include <unordered_set>
#include <utility>

#include "core/error.hpp"
#include "frame/frame.hpp"
#include "mesh/topology.hpp"

namespace quadapt::lpcvt {

namespace {

using Sym = Eigen::Matrix2d;

Sym sym_log(const Sym& A) {
  Eigen::SelfAdjointEigenSolver<Sym> es(A);
  const Eigen::Vector2d l = es.eigenvalues().array().log();
  return es.eigenvectors() * l.asDiagonal() * es.eigenvectors().transpose();
}

double mean_size(const Mat2& M) { return 1.0 / std::sqrt(std::abs(M.determinant())); }

std::vector<std::vector<int>> neighbours(const Background& bg) {
  Topology t = build_topology(bg.mesh());
  std::vector<std::vector<int>> nb(bg.mesh().num_cells());
  for (int c = 0; c < bg.mesh().num_cells(); ++c) nb[c] = t.neighbours(c);
  return nb;
}

/// The frame M = diag(sqrt(mu)) E^T of the Riemannian metric A (eigenpairs mu, E); nearly
/// isotropic A (stretch < 1.1): the isotropic frame of A's size turned like M0, (mu_0 mu_1)^(1/4) Q0
/// with Q0 the rotation nearest to M0 (its polar factor, reflection removed) — the eigenvectors
/// of such an A mean nothing, but the L_p energy sees the frame's orientation. (Keeping M0's whole
/// shape there, as before, kept a 5:1 frame where two crossing 5:1 frames average to a circle.)
Mat2 frame_of(const Sym& A, const Mat2& M0) {
  Eigen::SelfAdjointEigenSolver<Sym> es(A);
  const Eigen::Vector2d mu = es.eigenvalues();
  if (mu[1] / mu[0] < 1.1 * 1.1) {
    const Mat2 Mo = without_reflection(M0);
    // nearest rotation of [[a, b], [c, d]] (det > 0): R(-phi) with phi = atan2(c - b, a + d)
    const double phi = std::atan2(Mo(1, 0) - Mo(0, 1), Mo(0, 0) + Mo(1, 1));
    Mat2 Q;
    Q << std::cos(phi), -std::sin(phi), std::sin(phi), std::cos(phi);
    return std::pow(mu[0] * mu[1], 0.25) * Q;
  }
  Mat2 M = mu.array().sqrt().matrix().asDiagonal() * es.eigenvectors().transpose();
  // rows in the order and with the signs of M0's (the same |M u|_p either way; an unchanged
  // frame stays identical)
  if (std::abs(M.row(0).dot(M0.row(0))) + std::abs(M.row(1).dot(M0.row(1))) <
      std::abs(M.row(1).dot(M0.row(0))) + std::abs(M.row(0).dot(M0.row(1))))
    M.row(0).swap(M.row(1));
  for (int r = 0; r < 2; ++r)
    if (M.row(r).dot(M0.row(r)) < 0) M.row(r) *= -1;
  return M;
}

/// Metric intersection A ∩ B: with P^T A P = I, P^T B P = diag(l), A ∩ B = P^-T diag(max(1, l)) P^-1.
Sym intersect(const Sym& A, const Sym& B) {
  Eigen::GeneralizedSelfAdjointEigenSolver<Sym> es(B, A);  // B p = l A p, P^T A P = I
  const Mat2 P = es.eigenvectors();
  const Eigen::Vector2d l = es.eigenvalues().cwiseMax(1.0);
  const Mat2 Pi = P.inverse();
  Sym R = Pi.transpose() * l.asDiagonal() * Pi;
  return 0.5 * (R + R.transpose());
}

/// Rescales all metrics so that the metric area is `area` again; fills the report.
void restore_area(Background& bg, std::vector<Mat2>& M, double area, FilterReport& r) {
  bg.set_mesh_cell_metrics(M);
  r.rescale = bg.metric_area() > 0 ? std::sqrt(area / bg.metric_area()) : 1.0;
  for (Mat2& m : M) m *= r.rescale;
  bg.set_mesh_cell_metrics(M);
}

}  // namespace

double max_neighbour_size_ratio(const Background& bg) {
  const auto nb = neighbours(bg);
  double worst = 1;
  for (int c = 0; c < static_cast<int>(nb.size()); ++c) {
    const double hc = mean_size(bg.mesh_cell_metric(c));
    for (int n : nb[c]) worst = std::max(worst, mean_size(bg.mesh_cell_metric(n)) / hc);
  }
  return worst;
}

double metric_spread(const Background& bg) {
  const int n = bg.num_cells();
  std::vector<Sym> L(n);
  Sym mean = Sym::Zero();
  double area = 0;
  for (int c = 0; c < n; ++c) {
    const IntegrationCell& q = bg.cell(c);
    L[c] = sym_log(q.M.transpose() * q.M);
    mean += q.area * L[c];
    area += q.area;
  }
  if (!(area > 0)) return 0;
  mean /= area;
  double spread = 0;
  for (int c = 0; c < n; ++c) spread = std::max(spread, (L[c] - mean).norm());
  return spread;
}

FilterReport smooth_metric(Background& bg, int passes) {
  FilterReport r;
  if (bg.is_analytic()) throw InputError("", "metric smoothing needs a frame (piecewise-constant metric)");
  const int n = bg.mesh().num_cells();
  const auto nb = neighbours(bg);
  const double area = bg.metric_area();
  r.max_ratio_before = max_neighbour_size_ratio(bg);
  std::vector<Mat2> M0(n), M(n);
  std::vector<Sym> L(n), L2(n), L0(n);
  for (int c = 0; c < n; ++c) {
    M0[c] = bg.mesh_cell_metric(c);
    L[c] = L0[c] = sym_log(M0[c].transpose() * M0[c]);
  }
  for (int k = 0; k < passes; ++k) {
    for (int c = 0; c < n; ++c) {
      Sym s = L[c];
      for (int j : nb[c]) s += L[j];
      L2[c] = s / (1.0 + nb[c].size());
    }
    L.swap(L2);
  }
  for (int c = 0; c < n; ++c) {
    // a cell whose neighbourhood has its own metric (a constant frame) keeps its frame bit for bit
    // (the eigen rebuild would change it by rounding, which the minimisation amplifies)
    if ((L[c] - L0[c]).norm() <= 1e-12 * (1 + L0[c].norm())) {
      M[c] = M0[c];
      continue;
    }
    Eigen::SelfAdjointEigenSolver<Sym> es(L[c]);
    const Sym A = es.eigenvectors() * es.eigenvalues().array().exp().matrix().asDiagonal() * es.eigenvectors().transpose();
    M[c] = frame_of(A, M0[c]);
    if ((M[c] - M0[c]).norm() > 1e-12 * M0[c].norm()) ++r.cells_changed;
  }
  restore_area(bg, M, area, r);
  r.max_ratio_after = max_neighbour_size_ratio(bg);
  return r;
}

FilterReport grade_metric(Background& bg, double beta) {
  FilterReport r;
  if (bg.is_analytic()) throw InputError("", "metric gradation needs a frame (piecewise-constant metric)");
  if (!(beta > 1)) throw InputError("", "gradation growth must be > 1");
  const int n = bg.mesh().num_cells();
  const auto nb = neighbours(bg);
  const double area = bg.metric_area();
  const double lnb = std::log(beta);
  r.max_ratio_before = max_neighbour_size_ratio(bg);
  std::vector<Mat2> M0(n), M(n);
  std::vector<Sym> A(n);
  std::vector<Vec2> g(n);
  for (int c = 0; c < n; ++c) {
    M0[c] = bg.mesh_cell_metric(c);
    A[c] = M0[c].transpose() * M0[c];
    g[c] = cell_centroid(bg.mesh(), c);
  }
  // Finest first (Dijkstra's order): the cell of largest det 𝓜 (smallest area) imposes its bound
  // on its neighbours; a neighbour that changed is queued again with its new key. The order then
  // depends on the metrics alone, not on the cells' numbering: the intersection is not
  // associative, so a numbering-seeded worklist gave another frame for a turned or mirrored
  // frame, whose canonical order differs. Equal det: cells of one metric go one by one, lower
  // index first (the order changes only the rounding: η𝓜 ∩ 𝓜 = 𝓜 between them, and their bounds
  // on a neighbour are multiples of one 𝓜). Where *different* metrics share a det (diag(a, b)
  // beside diag(b, a)) the numbering would decide again, so that group goes at once: each member
  // imposes its bound from its metric before the group (a snapshot), and each neighbour takes the
  // bounds it receives in their own order, by the generalized eigenvalues of (bound, 𝓜_j), largest
  // first — all of it turning with the frame. (Exact ties of different metrics: none in PHiLiP's
  // frames; 1-4 in 4 of 34 study-loop frames sampled, all at step 0, before the smoothing.)
  using Key = std::pair<double, int>;
  auto later = [](const Key& a, const Key& b) { return a.first < b.first || (a.first == b.first && a.second > b.second); };
  std::priority_queue<Key, std::vector<Key>, decltype(later)> work(later);
  std::vector<char> changed(n, 0);
  std::vector<double> key(n);
  std::unordered_set<double> plain;  // det values seen at the top whose tie holds one metric only
  long updates = 0;
  const long max_updates = 200L * n + 1000;
  auto push = [&](int c) {
    work.push({key[c] = A[c].determinant(), c});
    plain.erase(key[c]);  // a newcomer to a tie: look at the tie again
  };
  for (int c = 0; c < n; ++c) push(c);
  auto bound = [&](const Sym& Ac, int c, int j) -> Sym {  // eta(l) 𝓜_c, l = |M_c (g_j - g_c)|
    const Vec2 d = g[j] - g[c];
    const double l = std::sqrt(d.dot(Ac * d));
    return (1.0 / ((1 + l * lnb) * (1 + l * lnb))) * Ac;
  };
  auto impose = [&](int j, const Sym& B) {
    const Sym I = intersect(A[j], B);
    if ((I - A[j]).norm() > 1e-9 * A[j].norm()) {
      A[j] = I;
      changed[j] = 1;
      ++updates;
      push(j);
    }
  };
  std::vector<Key> tied;
  std::vector<int> group;
  struct Bound {
    int j;
    double lmax, lmin;  // generalized eigenvalues of (B, 𝓜_j): the order-free sort key
    Sym B;
  };
  std::vector<Bound> bounds;
  // The whole tie at once, from a snapshot: c and the valid entries of `tied` (det k).
  auto process_group = [&](double k, int c) {
    group.assign(1, c);
    for (const Key& t : tied)
      if (key[t.second] == k && group.back() != t.second) group.push_back(t.second);
    bounds.clear();
    for (int m : group) {
      key[m] = -1;
      for (int j : nb[m]) bounds.push_back({j, 0, 0, bound(A[m], m, j)});
    }
    for (Bound& b : bounds) {
      Eigen::GeneralizedSelfAdjointEigenSolver<Sym> es(b.B, A[b.j]);
      b.lmax = es.eigenvalues()[1];
      b.lmin = es.eigenvalues()[0];
    }
    std::stable_sort(bounds.begin(), bounds.end(), [](const Bound& a, const Bound& b) {
      return a.j != b.j ? a.j < b.j : a.lmax != b.lmax ? a.lmax > b.lmax : a.lmin > b.lmin;
    });
    for (const Bound& b : bounds) impose(b.j, b.B);
  };
  while (!work.empty() && updates < max_updates) {
    const auto [k, c] = work.top();
    work.pop();
    if (k != key[c]) continue;  // a stale entry: c changed and was queued again
    if (!plain.count(k)) {  // do different metrics share this det? the tie's entries, in order
      bool mixed = false;
      tied.clear();
      while (!work.empty() && work.top().first == k) {
        tied.push_back(work.top());
        work.pop();
        if (key[tied.back().second] == k && A[tied.back().second] != A[c]) mixed = true;
      }
      if (mixed) {
        process_group(k, c);
        continue;
      }
      for (const Key& t : tied) work.push(t);
      plain.insert(k);
    }
    key[c] = -1;  // done until it changes again
    for (int j : nb[c]) impose(j, bound(A[c], c, j));
  }
  r.passes = static_cast<int>(updates);
  for (int c = 0; c < n; ++c) {
    M[c] = changed[c] ? frame_of(A[c], M0[c]) : M0[c];
    r.cells_changed += changed[c];
  }
  restore_area(bg, M, area, r);
  r.max_ratio_after = max_neighbour_size_ratio(bg);
  return r;
}

FilterReports filter_metric(Background& bg, int passes, double beta) {
  FilterReports r;
  if (passes > 0) r.smoothing = smooth_metric(bg, passes);
  if (beta > 0) r.gradation = grade_metric(bg, beta);
  return r;
}

FilterReport cap_metric(Background& bg, const std::vector<Mat2>& floor) {
  FilterReport r;
  if (bg.is_analytic()) throw InputError("", "metric capping needs a frame (piecewise-constant metric)");
  const int n = bg.mesh().num_cells();
  if (static_cast<int>(floor.size()) != n) throw NumericalError("cap_metric: one floor metric per background cell expected");
  const double area = bg.metric_area();
  r.max_ratio_before = max_neighbour_size_ratio(bg);
  std::vector<Mat2> M(n);
  for (int c = 0; c < n; ++c) {
    const Mat2 M0 = bg.mesh_cell_metric(c);
    const Sym A = M0.transpose() * M0;
    const Sym I = intersect(A, floor[c].transpose() * floor[c]);
    if ((I - A).norm() > 1e-12 * A.norm()) {
      M[c] = frame_of(I, M0);
      ++r.cells_changed;
    } else {
      M[c] = M0;
    }
  }
  restore_area(bg, M, area, r);
  r.max_ratio_after = max_neighbour_size_ratio(bg);
  return r;
}

}  // namespace quadapt::lpcvt
