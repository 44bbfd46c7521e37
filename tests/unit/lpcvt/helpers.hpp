#pragma once
// Shared helpers for the lpcvt unit tests: small in-memory domains and frames.
#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include <omp.h>

#include "lpcvt/background.hpp"
#include "lpcvt/boundary_points.hpp"
#include "lpcvt/energy.hpp"
#include "mesh/mesh.hpp"
#include "../worst.hpp"

namespace lpcvt_test {

/// Restores the OpenMP thread count when a test that changes it ends (also on a failed REQUIRE).
struct RestoreThreads {
  int saved = omp_get_max_threads();
  ~RestoreThreads() { omp_set_num_threads(saved); }
};

using quadapt::Mesh;
using quadapt::Vec2;
using namespace quadapt::lpcvt;

/// The §6.1 square [-1.3, 1.3]^2 as an n x n grid.
inline Mesh saddle_square(int n) { return quadapt::make_structured_quads(n, n, -1.3, 1.3, -1.3, 1.3); }

/// L-shape [0,2]^2 minus (1,2]x(1,2], as a 4x4 grid minus the top-right 2x2 block; no boundary
/// edges (the background derives them from the free edges).
inline Mesh l_shape() {
  Mesh g = quadapt::make_structured_quads(4, 4, 0, 2, 0, 2);
  Mesh m;
  m.nodes = g.nodes;
  for (int c = 0; c < g.num_cells(); ++c) {
    Vec2 z = quadapt::cell_centroid(g, c);
    if (z.x() > 1 && z.y() > 1) continue;
    m.cells.push_back(g.cells[c]);
  }
  return m;
}

/// [0,3]^2 minus the middle cell of a 3x3 grid (a square hole); no boundary edges.
inline Mesh square_with_hole() {
  Mesh g = quadapt::make_structured_quads(3, 3, 0, 3, 0, 3);
  Mesh m;
  m.nodes = g.nodes;
  for (int c = 0; c < g.num_cells(); ++c)
    if (c != 4) m.cells.push_back(g.cells[c]);
  return m;
}

/// Adds a constant "Vinv" field M = V^-1 with V = R(theta) diag(h1, h2).
inline void set_frame(Mesh& m, double h1, double h2, double theta) {
  quadapt::CellField f;
  f.name = "Vinv";
  f.ncomp = 9;
  f.values.assign(static_cast<size_t>(m.num_cells()) * 9, 0.0);
  Mat2 R;
  R << std::cos(theta), -std::sin(theta), std::sin(theta), std::cos(theta);
  Mat2 V = R * Eigen::Vector2d(h1, h2).asDiagonal();
  Mat2 M = V.inverse();
  for (int c = 0; c < m.num_cells(); ++c) {
    f(c, 0) = M(0, 0);
    f(c, 1) = M(0, 1);
    f(c, 3) = M(1, 0);
    f(c, 4) = M(1, 1);
    f(c, 8) = 1;
  }
  m.set_field(f);
}

/// n uniform random points strictly inside the background's cells (rejection in the bbox).
inline std::vector<Vec2> random_inside(const Background& bg, int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> ux(bg.lo().x(), bg.hi().x()), uy(bg.lo().y(), bg.hi().y());
  std::vector<Vec2> p;
  while (static_cast<int>(p.size()) < n) {
    Vec2 y(ux(rng), uy(rng));
    if (bg.inside(y)) p.push_back(y);
  }
  return p;
}

/// The boundary points of bg's domain (mesh_boundary; nfixed of them) followed by n random points inside.
inline std::vector<Vec2> boundary_and_random(const Background& bg, int n, unsigned seed, int& nfixed) {
  BoundaryPoints b = mesh_boundary(bg, boundary_curves(bg));
  std::vector<Vec2> s = b.points;
  nfixed = static_cast<int>(s.size());
  auto in = random_inside(bg, n, seed);
  s.insert(s.end(), in.begin(), in.end());
  return s;
}

/// M with M^T M of sizes h1 along (cos theta, sin theta), h2 across.
inline Mat2 rotated_metric(double h1, double h2, double theta) {
  Mat2 M;
  const double c = std::cos(theta), s = std::sin(theta);
  M << c / h1, s / h1, -s / h2, c / h2;
  return M;
}

/// A graded frame with metric cells on the saddle square (12 x 12 cells): sizes 4x apart across
/// the square, 5:1, the direction rotating with y.
inline Background graded_metric_background() {
  Mesh m = saddle_square(12);
  set_frame(m, 0.2, 0.04, 0.3);
  quadapt::CellField* f = m.cell_field("Vinv");
  for (int c = 0; c < m.num_cells(); ++c) {
    const Vec2 z = (m.nodes[m.cells[c].v[0]] + m.nodes[m.cells[c].v[2]]) / 2;
    const double s = std::pow(4.0, (z.x() + 1.3) / 2.6), th = 0.3 + 0.8 * z.y();
    const Mat2 M = rotated_metric(0.2 / s, 0.04 / s, th);
    for (int r = 0; r < 2; ++r)
      for (int q = 0; q < 2; ++q) f->values[9 * c + 3 * r + q] = M(r, q);
  }
  Background bg = Background::from_frame(m, 1.0, "mem");
  bg.set_metric_cells(true);
  return bg;
}

/// Max over the free sites x[nfixed..] of |g_fd - g| / |g|: the L_6 energy's gradient (weight
/// |det M|^gamma) against fourth-order central differences with step h.
inline double fd_worst(const Background& bg, const std::vector<Vec2>& x, int nfixed, double h,
                       double gamma = 0) {
  const EnergyResult r = lp_energy(bg, x, 6, true, nullptr, gamma);
  double worst = 0;
  for (int i = nfixed; i < static_cast<int>(x.size()); ++i) {
    Vec2 fd;
    for (int d = 0; d < 2; ++d) {
      auto at = [&](double off) {
        std::vector<Vec2> y = x;
        y[i][d] += off;
        return lp_energy(bg, y, 6, false, nullptr, gamma).energy;
      };
      fd[d] = (-at(2 * h) + 8 * at(h) - 8 * at(-h) + at(-2 * h)) / (12 * h);
    }
    worst = quadapt_test::worst_of(worst, (fd - r.grad[i]).norm() / r.grad[i].norm());
  }
  return worst;
}

}  // namespace lpcvt_test
