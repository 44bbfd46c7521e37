#pragma once
// Triangles -> quads by a maximum-weight matching of the dual graph in the frame's metric
// (issue #14; LEMON's MaxWeightedMatching, general graphs, Edmonds' blossom algorithm).
//
// Gmsh's Blossom-Quad (quad/blossom.hpp) finds a minimum-cost PERFECT matching with a
// physical-space cost. On a lattice that is square in a stretched metric, (a) every physical
// quad is a thin rectangle or parallelogram, so the physical cost hardly tells the frame's
// rectangles from sheared pairs, and (b) perfection forces every parity defect where the
// lattice meets the boundary to be joined to another by a chain of sheared pairs (a column of
// 45-degree parallelograms in the metric across the domain).
//
// Here: nodes = triangles, an edge for every interior mesh edge whose two triangles form a
// strictly convex quad (in physical space: a valid cell); its quality in the metric
//     q = 1 - max_k |theta_k - 90 deg| / 90 deg          (theta_k the quad's corner angles)
// with the corners mapped by L^T, L L^T = (G_a + G_b) / 2, G = M^T M of the two triangles
// (1 for a square in the metric, 0.5 for a 45-degree parallelogram, 0 when not convex in the
// metric). Weight
//     w = round(1000 (q + pair_bonus + interior_bonus n_i))   (with min_quality > 0, edges with q <= it
//                                                             are left out)
// (n_i = how many of the pair's two triangles have no edge on the boundary)
// and the matching maximises the total weight without having to be perfect: a chain of k
// sheared pairs loses to two unmatched triangles as soon as k (q_square - q_sheared) exceeds
// q_square + pair_bonus, so defects stay local, while on irregular point sets (graded frames)
// the bonus keeps the unmatched triangles few (each becomes three quads and an irregular vertex). Unmatched triangles remain triangles (the split
// to all-quad turns each into three quads). Integer weights: the result is exact and
// deterministic (LEMON's ListGraph, nodes and edges added in cell / edge order).
//
// The interior bonus (beyond the thesis; issue #14): where a lattice that is square in the metric
// meets a wall obliquely, its rows end in lone triangles one row inside the wall. A lone
// triangle becomes three quads around a valence-3 vertex, and the row's end leaves a vertex in
// five cells beside it: a 3-5 pair of irregular interior vertices. Paying interior_bonus for
// every matched triangle that has no boundary edge makes the matching leave the lone triangle
// AT the wall when that costs little pair quality; the five-cell vertex is then a wall vertex
// (three cells, not an interior defect). On the constant frames of docs/quad-quality.md at
// 45°, 5:1 the interior irregular vertices fall from 36 to 24 of 921 (the 20 lone triangles
// stay, 22 valence-3 vertices; the valence-5 ones go from 14 to 2), and every row meets
// issue #14's 3 % (docs/recombine.md for the figures and the cost on the loops).
#include <Eigen/Core>
#include <vector>

#include "mesh/mesh.hpp"

namespace quadapt {

struct MetricMatchingOptions {
  double min_quality = 0;     ///< > 0: pairs of metric quality <= this are never matched
  double pair_bonus = 0.5;    ///< added to every pair's weight: rewards pairing over leaving triangles
  double interior_bonus = 0.1;  ///< added per triangle of the pair without a boundary edge (above)
};

struct MetricMatchingStats {
  int triangles_in = 0;
  int quads = 0;               ///< matched pairs
  int triangles = 0;           ///< left unmatched
  int wall_triangles = 0;      ///< of those, the ones with an edge on the boundary
  double mean_quality = 0;     ///< of the matched pairs
  int candidate_pairs = 0;     ///< dual edges with q > min_quality
};

/// Quality q (above) of the quad (a, b, c, d) (CCW) mapped by the 2x2 factor F (any F with
/// F^T F = the metric): in [0, 1], 0 when not strictly convex (a corner whose angle's sine is at
/// most min_sine).
double metric_quad_quality(const Eigen::Matrix2d& F, const Vec2& a, const Vec2& b, const Vec2& c,
                           const Vec2& d, double min_sine = 1e-12);

/// A pair is a candidate only when every corner of its quad in physical space has an angle whose
/// sine exceeds this: a corner straight up to rounding (three corners in line: lpcvt put a point on
/// the line between two others, to ~1e-12) makes a quad that validate_mesh may refuse. The smallest
/// sine chosen on ordinary frames (constant frames of stretch 1-20 at 0-75 degrees, PHiLiP's step-3
/// frames) is 5e-3.
constexpr double kMinPairSine = 1e-6;

/// Pairs the triangles of `tri` (all triangles, CCW, boundary groups kept) into quads; `M`: one
/// 2x2 frame matrix per triangle (M^T M the metric; an empty vector: the identity, i.e. physical
/// space). The result has the matched quads then the unmatched triangles, in cell order.
Mesh metric_pairing(const Mesh& tri, const std::vector<Eigen::Matrix2d>& M,
                    const MetricMatchingOptions& opt = {}, MetricMatchingStats* stats = nullptr);

}  // namespace quadapt
