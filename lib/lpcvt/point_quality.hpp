#pragma once
// Measurements of L_p-CVT results (tests, reports, docs): angles of the output triangles in the
// metric (M_eff at the centroid maps a triangle to the metric space, where the target is a
// right isosceles triangle, half of a unit square), the alignment of the clipped Voronoi cells
// with the metric axes, Delaunay valences, and a JSON dump of the clipped Voronoi diagram for
// pictures.
#include <array>
#include <vector>

#include <nlohmann/json.hpp>

#include "lpcvt/background.hpp"

namespace quadapt::lpcvt {

struct AngleStats {
  int triangles = 0;
  double median_largest = 0;     ///< degrees: median over triangles of the largest angle
  double mean_largest = 0;
  double frac_largest_80_100 = 0;///< share of triangles whose largest angle is in [80, 100]
  double median_smallest = 0;
};
/// Largest/smallest angles of the triangles of `tri` measured in the metric space of `bg`
/// (metric = true) or in physical space.
AngleStats triangle_angles(const Background& bg, const Mesh& tri, bool metric = true);

struct AlignmentStats {
  double mean_deviation = 0;  ///< degrees: length-weighted mean over Voronoi edges of the angle,
                              ///< in metric space, to the nearest metric axis (0..45)
  double frac_within_10 = 0;  ///< length share of edges within 10 degrees of an axis
  int edges = 0;
};
/// Alignment of the Voronoi edges (bisectors of the restricted diagram, boundary excluded) of
/// the sites `from..` (e.g. only free sites), weighted by metric length.
///  principal = false: with the axes of M_eff: an edge u is aligned when M_eff u is parallel to
///    e1 or e2 (cells are the images of unit squares; the frame's parallelogram).
///  principal = true: with the principal directions of M_eff^T M_eff in physical space (the
///    eigenvectors; for a frame these are v and w, for the symmetric metric of eq. 6.1 the
///    directions of the metric ellipse, which rectangular Voronoi cells can follow).
AlignmentStats voronoi_alignment(const Background& bg, const std::vector<Vec2>& sites, int from = 0,
                                 bool principal = false);
/// Both of the above ({axes, principal}) from one restricted Voronoi diagram, its pieces made in
/// parallel over the background cells (sums per cell, added in cell order: the figures do not
/// depend on the thread count).
std::array<AlignmentStats, 2> voronoi_alignments(const Background& bg, const std::vector<Vec2>& sites, int from = 0);

/// Valence (number of Delaunay neighbours) histogram of sites[from..], index = valence.
std::vector<int> valence_histogram(const std::vector<Vec2>& sites, int from = 0);

/// {"sites": [[x,y]...], "nfixed": n, "edges": [[x1,y1,x2,y2]...] (Voronoi edges inside the
/// domain, each once), "boundary": [[x1,y1,x2,y2]...] (the domain boundary)}.
nlohmann::json voronoi_json(const Background& bg, const std::vector<Vec2>& sites, int nfixed);

}  // namespace quadapt::lpcvt
