#pragma once
// Node insertion and removal (thesis §4.5, Algorithm 2).
//
// Every Delaunay edge e = (x1, x2) of the sites is measured by the L_q line integral (eq. 4.12)
//     L(e) = integral_0^1 |M_eff(x1 + t (x2 - x1)) (x2 - x1)|_q dt      (q = the L_p exponent)
// Edges longer than lmax are split (a new site at the midpoint); edges shorter than lmin are
// merged (both sites replaced by the midpoint; when one of them is a fixed boundary site, the
// free one is removed). Edges are visited from the most out-of-range one (largest L / lmax or
// lmin / L) down; a site touched once is flagged and its other edges are ignored in this pass.
// Boundary segments (consecutive fixed boundary sites) are never split, nor a chord between two
// boundary sites that runs along the boundary (its midpoint within 0.05 of its length of the
// boundary polyline: on a straight wall oblique to the axes the wall points are collinear
// only up to rounding, and the Delaunay graph may join two of them across a third — a split
// there put a free site on the wall); an edge whose midpoint lies outside the domain (a chord
// across a re-entrant corner or a hole) is ignored.
//
// Beyond the thesis (option metric_delaunay, default on): only edges that are also Delaunay in
// the local metric are measured (the four points of the edge's two triangles mapped by M_eff at
// the edge midpoint pass the in-circle test). With strong anisotropy the Euclidean Delaunay
// graph has edges that skip a row of points (metric length ~2 in a staggered lattice); splitting
// them inserts points between rows that the next cycle merges again (split/merge churn).
//
// Before measuring, free sites outside the domain and duplicates are removed (counted apart).
#include <array>
#include <vector>

#include "lpcvt/background.hpp"

namespace quadapt::lpcvt {

struct SplitMergeOptions {
  double q = 6;       ///< norm of the line integral (eq. 4.12), normally the L_p exponent
  double lmin = 0.25;  ///< merge below (metric units of M_eff; thesis §4.5: [0.25, 2])
  double lmax = 2.0;   ///< split above
  int samples = 8;    ///< midpoint-rule samples per edge
  bool metric_delaunay = true;  ///< measure only edges that are Delaunay in the local metric
};

struct SplitMergeResult {
  int edges = 0;            ///< Delaunay edges measured
  int splits = 0;
  int merges = 0;
  int removed_outside = 0;  ///< free sites outside the domain or duplicated, removed
  double min_length = 0, max_length = 0, mean_length = 0;  ///< over the measured edges
  double change_fraction() const { return edges ? double(splits + merges) / edges : 0.0; }
};

/// Applies Algorithm 2 to sites[nfixed..] (sites[0..nfixed) are fixed and kept in place, in
/// order). Surviving free sites keep their order; new sites are appended.
SplitMergeResult split_merge(const Background& bg, std::vector<Vec2>& sites, int nfixed,
                             const std::vector<std::array<int, 2>>& boundary_segments,
                             const SplitMergeOptions& opt);

/// Brings the number of sites to `target` (beyond the thesis: complexity honesty): when there
/// are too few, the longest measured Delaunay edges (eq. 4.12, as in split_merge, boundary
/// segments and chords along the boundary excluded) get a new site at their midpoint; when there
/// are too many, the shortest edges are merged (as in split_merge). Each site takes part in one change per pass; passes
/// repeat until the count is reached (at most 8). Fixed sites stay. Returns the change made
/// (positive: sites added).
int adjust_count(const Background& bg, std::vector<Vec2>& sites, int nfixed,
                 const std::vector<std::array<int, 2>>& boundary_segments, int target,
                 const SplitMergeOptions& opt);

/// Removes free sites (index >= nfixed) outside the domain (or not finite), or coinciding with an
/// earlier site; returns how many.
int remove_outside(const Background& bg, std::vector<Vec2>& sites, int nfixed);

}  // namespace quadapt::lpcvt
