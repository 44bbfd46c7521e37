#pragma once
// The Delaunay graph of the sites in the frame's metric (anisotropic Voronoi cells, issue #14).
//
// Why: the L_p-CVT energy partitions the domain into Voronoi cells. Euclidean cells (the thesis)
// match the frame's rectangles only when the frame is aligned with the x/y axes; in a frame
// stretched 10:1 the Euclidean partition leaves shear modes of the point lattice almost free, and
// an oblique boundary drives the points to a hexagonal pattern (measured: 41 % of edges in band
// at 30 degrees, 98 % at 0 degrees). With cells built in the metric, every constant-frame problem
// is the isotropic problem of the metric space y = M x, where the square lattice is stiff.
//
// Definition. In integration cell Q (constant metric M_Q, G_Q = M_Q^T M_Q) the cell of site i is
//   { y in Q : (y - x_i)^T G_Q (y - x_i) <= (y - x_j)^T G_Q (y - x_j)  for all j },
// bounded by the G-bisectors  2 (x_j - x_i)^T G_Q y = x_j^T G_Q x_j - x_i^T G_Q x_i  (straight
// lines in x, so the pieces stay convex polygons). The neighbours j that matter are those of the
// Delaunay triangulation of the mapped sites M_Q x. We take the Euclidean Delaunay triangulation
// and apply Lawson flips with the metric in-circle test, the metric of a flip quadrilateral being
// that of the background cell at its centroid (the mean of its four corners): for a constant metric this gives exactly the Delaunay
// triangulation of the mapped sites (Lawson's flip algorithm in the mapped plane; convexity of
// the flip quadrilateral is affine-invariant); for a graded metric, the local one.
//
// Flip order: the most violated edge first (the largest in-circle value; a priority queue, ties
// by triangle and edge index). Where the metric varies, Lawson's flips are not confluent: the
// triangulation they end in depends on the order, and an order that follows the triangles'
// numbering (a stack seeded from triangle 0) does not turn with the problem — on PHiLiP's frames
// turned by 90 degrees or mirrored, split/merge and the exact count then saw other edges and
// lpcvt's points moved by up to 0.06 of the domain. The in-circle values turn with the problem
// (docs/quad-quality.md, "Turned and mirrored graded frames"; tests/cli/graded_equivariance.sh).
//
// Flip rule: edge (a, b) with opposite vertices c (triangle a b c, CCW) and d is flipped when d is
// strictly inside the circle through M a, M b, M c (the in-circle determinant over the product
// of the two diagonals' squared mapped lengths above 1e-9, so that co-circular squares of a
// metric lattice stay as they are) and the
// quadrilateral a d b c is strictly convex. The metric belongs to the quadrilateral, not to the
// edge: the test of the flipped diagonal (c, d) in the same quadrilateral uses the same metric and
// so never asks to flip back. With the metric at the edge's midpoint instead, the two diagonals
// of a quadrilateral straddling a metric jump see different metrics and flip back and forth
// (an S-shock frame, 1623 triangles: 16,780 flips until the cap, a cell with scaled Jacobian
// 0.007 in the quads). An edge a flip removed is never made again, so the flips end for any
// metric (at most one per pair of sites).
//
// Flip cap (kMaxFlipsPerSite): how many flips there are grows with the metric's stretch, since
// they start from the Euclidean triangulation — per site, measured on lpcvt's sites of constant
// frames at 30 degrees: 5 at 20:1, 18-24 at 100-300:1, 47-100 at 1000:1. The cap bounds their
// time and the memory of the removed edges where a pathological case would need far more;
// reaching it leaves a triangulation that is not the metric Delaunay one (`capped`). It was 20
// per site, which cut every 1000:1 frame's flips short, silently: lpcvt's output kept long
// Euclidean triangles (median largest metric angle 179.8 degrees instead of 76-89) and the
// energy's neighbours were wrong (a 1000:1 frame: 130 evaluations instead of 14, 10x the time).
#include <array>
#include <functional>
#include <unordered_set>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "mesh/mesh.hpp"

namespace quadapt::lpcvt {

/// The most Lawson flips per site of one metric_delaunay / metric_delaunay_update (header): twice
/// the most measured at 1000:1.
constexpr long kMaxFlipsPerSite = 200;

struct MetricGraph {
  std::vector<int> ptr, adj;               ///< CSR neighbour lists, #sites + 1 / 2 #edges
  std::vector<std::array<int, 3>> tris;    ///< the flipped triangles, CCW
  std::vector<std::array<int, 3>> tnb;     ///< tnb[t][k]: the triangle across the edge opposite
                                           ///< tris[t][k] (-1: none), for metric_delaunay_update
  long flips = 0;                          ///< flips made (by the last build or update)
  long inverted = 0;                       ///< inverted triangles carried (metric_delaunay_update)
  bool capped = false;                     ///< the flip cap (kMaxFlipsPerSite) was reached
  /// Buffers of the flips, kept between updates (an evaluation of the energy carries the graph
  /// and updates it every time: no allocation once they are large enough). Not part of the graph.
  struct Scratch {
    /// An edge that wants a flip: in-circle value, triangle t and edge k (opposite tris[t][k]),
    /// the neighbour u across it and the versions of t and u when the value was computed.
    struct Want {
      double value;
      int t, k, u, vt, vu;
    };
    std::vector<Want> heap;
    std::vector<std::vector<Want>> part;  ///< per block: its edges that want a flip
    std::vector<int> version;             ///< per triangle: bumped when it or a neighbour changes
    std::vector<int> fill;
    std::unordered_set<long long> removed;
  } scratch;
  int num_sites() const { return static_cast<int>(ptr.size()) - 1; }
  const int* nbr_begin(int i) const { return adj.data() + ptr[i]; }
  const int* nbr_end(int i) const { return adj.data() + ptr[i + 1]; }
};

/// The metric (2x2, any matrix whose M^T M is the Riemannian metric) to use for the flip
/// quadrilateral with these four corners (the same for both of its diagonals); the zero matrix:
/// never flip there.
using EdgeMetric = std::function<Eigen::Matrix2d(const std::array<Vec2, 4>& corners)>;

/// Makes independent EdgeMetric objects (each may keep state, e.g. a point-location hint): with
/// it, the first in-circle test of every edge is made in parallel (OpenMP, fixed blocks of 4,096
/// triangles, one fresh metric per block) and only the edges that want a flip are queued for the
/// serial Lawson loop (whose flips queue the four outer edges of each flipped quadrilateral as
/// always). The result does not depend on the thread count. It is
/// the graph of the call without a factory when the metric's answer does not depend on its state;
/// a stateful metric may differ there (the background's point location puts a point within its
/// tolerance of a cell edge in either cell, by where its walk starts), so the two graphs can
/// differ where such a tie changes a flip decision.
using EdgeMetricFactory = std::function<EdgeMetric()>;

/// Lawson flips of the triangulation `tris` (CCW triangles over `sites`, e.g. the Euclidean
/// Delaunay triangulation; a manifold triangulation: every interior edge in exactly two triangles)
/// by the metric in-circle test, then the neighbour lists.
MetricGraph metric_delaunay(const std::vector<Vec2>& sites, std::vector<std::array<int, 3>> tris,
                            const EdgeMetric& metric, const EdgeMetricFactory& parallel_metric = {});

/// Carries `g` (a metric graph of these sites' earlier positions, e.g. the last energy
/// evaluation's) to the positions `sites`: when at most `max_inverted` triangles of g are no
/// longer counter-clockwise, Lawson flips by the same rule, from g's triangles instead of the
/// Euclidean Delaunay triangulation, and true (g.inverted counts the inverted triangles carried
/// so far); else false and g unchanged (the caller rebuilds). With no inverted triangle, wherever
/// the flip rule has one answer (a constant metric, no four sites co-circular in it) the result
/// is the graph a rebuild gives; on co-circular quadrilaterals (within the 1e-9 tolerance, e.g. a
/// metric lattice's squares) the carried diagonal stays where a rebuild keeps the Euclidean one,
/// and where the metric varies the flips' order (hence the result) differs from a rebuild's.
/// An inverted triangle leaves a few wrong or missing neighbours near it. Any of these graphs
/// serves the energy, whose pieces do not depend on the graph beyond rounding (rvd.hpp: every
/// site within the security radius of what the neighbours leave clips the piece).
bool metric_delaunay_update(const std::vector<Vec2>& sites, MetricGraph& g, const EdgeMetric& metric,
                            int max_inverted = 0, const EdgeMetricFactory& parallel_metric = {});

/// In-circle test of d against the circle through a, b, c (CCW) in the metric M: > 0 inside.
/// Depends on M^T M only (a reflection, det M < 0, gives the same answer). Dimensionless: the
/// in-circle determinant divided by |M(d - a)|^2 |M(c - b)|^2, which for d across the edge b c
/// (the flip quadrilateral a b d c) is the product of its two diagonals' squared lengths — the
/// determinant (an even permutation) and this scale are the same tested from either side of the
/// edge (a b c against d, or d c b against a), so the value belongs to the quadrilateral, not to
/// the triangle it is tested from, which follows the numbering (metric_graph.hpp "Flip order";
/// with the test point's distances as the scale, the flips' order followed the side).
double metric_incircle(const Eigen::Matrix2d& M, const Vec2& a, const Vec2& b, const Vec2& c,
                       const Vec2& d);

}  // namespace quadapt::lpcvt
