#pragma once
// The L_p-CVT energy and its analytic gradient (thesis eqs. 4.1, 4.8-4.11).
//
//   E(x) = sum_i integral over (Omega_i ∩ Omega) of |M(y) (y - x_i)|_p^p dy           (4.1)
//
// with Omega_i the Euclidean Voronoi cell of site x_i, M = M_eff of the background and
// |F|_p^p = |F_0|^p + |F_1|^p. The integral is split into the pieces Omega_i ∩ Q of the
// restricted Voronoi diagram (lpcvt/rvd.hpp); each convex piece is fanned from its first vertex
// into facets (c0, c_k, c_k+1) and integrated with a triangle rule (fem/quadrature.hpp;
// exact for p <= 6 even with a constant metric), eq. 4.8.
//
// Gradient, eq. 4.9: dE/dx_s = sum over facets of the direct term (the integrand depends on
// x_i; eq. 4.10 without the facet motion) plus, for every facet vertex c, (dI/dc)(dc/dx_s)
// (eq. 4.11 and the chain rule). dI/dc collects the integrand's variation with the quadrature
// points (including dM/dy for analytic metrics) and the Jacobian's. A vertex c is the
// intersection of two lines n_r . c = d_r (r = 1, 2); for the bisector of (i, j),
// g = (x_j - x_i) . c - (|x_j|^2 - |x_i|^2) / 2 = 0, so with A = [n_1; n_2],
//   dc/dx_s = -A^-1 [dg_r/dx_s],  dg/dx_i = (x_i - c)^T,  dg/dx_j = (c - x_j)^T;
// background edges are fixed lines. This covers Voronoi vertices (circumcentres, [74]) and
// clipped vertices on the boundary or on a background edge ([10]) alike. The result is the exact
// derivative of the discrete (quadrature) energy, so it matches finite differences to rounding.
//
// Closed form (beyond the thesis, for speed): with a constant metric on the piece and an even
// integer p, each component F_r = m_r . (y - x_i) is linear on a facet T with vertex values
// a, b, c, and
//   integral over T of F_r^p = |T| 2 / ((p+1)(p+2)) h_p(a, b, c),
// h_p the complete homogeneous symmetric polynomial of degree p (sum of all a^i b^j c^k with
// i+j+k = p; from  integral of l1^i l2^j l3^k = 2|T| i! j! k! / (i+j+k+2)!), with
//   d h_p(a, b, c) / da = h_{p-1}(a, a, b, c).
// Both are evaluated by the recurrence h_n(..., z) = h_n(...) + z h_{n-1}(..., z) in O(p)
// operations, about 6x fewer than the 12-point rule (same values up to rounding); p = 2..12.
// Analytic metrics and other p use the quadrature rule.
//
// Weighted energy (beyond the thesis; option gamma, 1 for frames by default):
//   E_w(x) = sum_i integral over Omega_i of omega(y) |M(y) (y - x_i)|_p^p dy,  omega = |det M|^gamma.
// Why: in a region of constant metric with n points on area A, each cell has the metric area
// s = A det M / n and the energy n C s^((p+2)/2) / det M; minimising the sum over regions for
// a fixed total count balances E_r / n_r, which gives s ∝ (det M)^(2/(p+2)) (gamma = 0): the
// thesis's energy puts fewer points than the metric asks where it is fine (det M large) and
// more where it is coarse — with p = 6 and a 20x finer boundary layer the layer gets
// (400)^(1/4) = 4.5x too little metric density. With omega = |det M| (gamma = 1) the balance
// gives s = const: one point per unit metric area everywhere, as the frame asks (the energy is
// then the integral over the metric space). Within a region of constant metric the weight is a
// constant factor, so the optimal lattice and its orientation are unchanged. Analytic metrics
// include d omega / dy = gamma omega tr(M^-1 dM/dy) in the gradient.
//
// Parallel over integration cells (OpenMP); per-cell contributions are summed afterwards in
// cell order, so the result does not depend on the thread count. An EnergyWorkspace keeps the
// buffers between evaluations (no allocation once warm).
#include <memory>
#include <utility>
#include <vector>

#include "lpcvt/background.hpp"
#include "lpcvt/rvd.hpp"

namespace quadapt::lpcvt {

struct EnergyResult {
  double energy = 0;
  std::vector<Vec2> grad;  ///< dE/dx_i for every site (fixed sites included); empty if not asked
  long pieces = 0;         ///< number of clipped-cell pieces integrated
};

/// How the energy is evaluated (no effect on the value beyond rounding).
struct EnergySettings {
  bool closed_form = true;        ///< the closed form (above) where it applies; tests compare both paths
  bool carry_metric_graph = true;  ///< metric cells: carry the metric graph between evaluations by
                                   ///< flips (update_metric_graph) instead of rebuilding it from a
                                   ///< Euclidean Delaunay graph (changes the rounding only)
  double carry_inverted = 1e-3;    ///< ... while at most this fraction of its triangles invert at
                                   ///< an evaluation, and 10x that have since the last rebuild
  int tree_refits = 20;            ///< metric cells, carried graph: the site tree of the evaluation
                                   ///< before refitted (SiteTree::refit) this many times in a row,
                                   ///< then built anew (0: always built anew; the same pieces either way)
  int grid_min_sites = RestrictedVoronoi::kGridMinSites;  ///< metric cells: an integration cell with about this many sites or
                                   ///< more answers its security searches from a bucket grid
                                   ///< (cell_grid.hpp; 0: the site tree always; the same pieces)
  int min_parallel_sites = 2000;  ///< OpenMP from this many sites on (smaller problems lose more to
                                  ///< thread start-up than they gain); tests set 0 for the parallel path
};

/// Wall seconds spent by one workspace in the two phases of the convenience lp_energy: the
/// Delaunay graph and start sites, and the pieces + integration.
struct EnergyTimers {
  double delaunay = 0, integrate = 0;
  long evaluations = 0;
  long updates = 0, rebuilds = 0;  ///< Delaunay graphs updated by flips / rebuilt
  long carried = 0;                ///< metric cells: metric graphs carried from the evaluation before
  long tree_refits = 0;            ///< ... with the site tree refitted, not built anew
  long grid_searches = 0;              ///< metric cells' security-radius searches answered by a
                                       ///< cell's bucket grid (cell_grid.hpp); the others:
  long box_queries = 0, box_hits = 0;  ///< metric cells' security-radius searches: site-tree
                                       ///< queries / answered from a cached box (rvd.hpp)
  long ellipse_queries = 0;            ///< ... answered by an ellipse query of the site tree (rvd.hpp)
  EnergyTimers& operator+=(const EnergyTimers& o);
};

/// Buffers reused between evaluations (per-cell gradient contributions, per-thread pieces),
/// the evaluation settings and the time spent.
class EnergyWorkspace {
 public:
  EnergyWorkspace();
  explicit EnergyWorkspace(const EnergySettings& s);
  ~EnergyWorkspace();
  EnergySettings settings;
  EnergyTimers timers;
  struct Impl;
  std::unique_ptr<Impl> impl;
};

/// E and dE/dx on the restricted Voronoi diagram `rvd` (built on the same background).
/// `gamma` != 0: the weighted energy (above) with omega = |det M_eff(y)|^gamma.
EnergyResult lp_energy(const RestrictedVoronoi& rvd, const Background& bg, double p,
                       bool gradient = true, EnergyWorkspace* ws = nullptr, double gamma = 0);

/// Convenience: builds the restricted Voronoi diagram of `sites` first.
EnergyResult lp_energy(const Background& bg, const std::vector<Vec2>& sites, double p,
                       bool gradient = true, EnergyWorkspace* ws = nullptr, double gamma = 0);

/// The edges {i, j} of the neighbour graph of the workspace's last evaluation, each once (i < j),
/// by i and then in the order of i's neighbour list (the metric graph's lists are sorted, so
/// there the pairs are too): the metric graph with metric cells, else the Delaunay graph; empty
/// before any evaluation.
std::vector<std::pair<int, int>> last_graph_edges(const EnergyWorkspace& ws);

/// Energy of one piece (tests): integral over the piece of |M (y - x_site)|_p^p.
double piece_energy(const RvdPiece& piece, const Background& bg, const Vec2& x_site, double p);

}  // namespace quadapt::lpcvt
