#pragma once
// The Delaunay graph of the L_p-CVT sites (CGAL Delaunay_triangulation_2, exact predicates;
// CGAL stays inside delaunay.cpp). The Voronoi cell of site i is the intersection of the
// half-planes  |y - x_i| <= |y - x_j|  over its Delaunay neighbours j (thesis §3.2).
//
// Sites that coincide exactly with an earlier site are "hidden": they get no neighbours and no
// cell (CGAL keeps one vertex per position).
#include <array>
#include <memory>
#include <vector>

#include "mesh/mesh.hpp"

namespace quadapt::lpcvt {

class DelaunayGraph {
 public:
  /// `with_triangles = false` skips the (sorted) triangle list (the energy evaluation needs only
  /// the neighbours); `with_voronoi` also stores the Voronoi polygons of the sites not on the
  /// convex hull (circumcentres of the Delaunay triangles around them).
  explicit DelaunayGraph(const std::vector<Vec2>& sites, bool with_triangles = true,
                         bool with_voronoi = false);
  ~DelaunayGraph();
  DelaunayGraph(DelaunayGraph&&) noexcept;
  DelaunayGraph& operator=(DelaunayGraph&&) noexcept;

  /// Moves the sites to `sites` (same count) keeping the triangulation: the "reuse between
  /// evaluations where points move little" of the energy evaluation. The sites are moved where
  /// no triangle inverts and the hull stays (the others, at most 5% + 10, stay put for now), the
  /// Delaunay property is restored by edge flips (Lawson), and the remaining sites are moved one
  /// by one with CGAL's move. The result is the Delaunay triangulation of the new sites (unique
  /// under CGAL's symbolic perturbation; the neighbour lists start at the smallest neighbour, so
  /// the tables are the same as after a rebuild). Rebuilds from scratch when there are hidden
  /// (duplicate) sites, too many inverted triangles, or a collision. Returns true when the update
  /// sufficed. `flips` receives the number of flips.
  bool update(const std::vector<Vec2>& sites, int* flips = nullptr);

  int num_sites() const { return static_cast<int>(ptr_.size()) - 1; }
  /// Finite Delaunay neighbours of site i, counter-clockwise: [nbr_begin(i), nbr_end(i)).
  const int* nbr_begin(int i) const { return adj_.data() + ptr_[i]; }
  const int* nbr_end(int i) const { return adj_.data() + ptr_[i + 1]; }
  int degree(int i) const { return ptr_[i + 1] - ptr_[i]; }
  bool hidden(int i) const { return hidden_[i] != 0; }
  /// True when site i is on the convex hull (an infinite Delaunay face is incident), or hidden.
  bool on_hull(int i) const { return hull_[i] != 0; }
  /// With `with_voronoi`, for a site i not on the hull: its (bounded) Voronoi polygon,
  /// counter-clockwise, [vor_begin(i), vor_begin(i) + degree(i)): vertex k is the circumcentre
  /// of the Delaunay triangle (i, n_k, n_k+1) (n = the neighbours in their CCW order), so the
  /// polygon edge from vertex k to vertex k+1 lies on the bisector of i and n_k+1.
  const Vec2* vor_begin(int i) const { return vor_.data() + ptr_[i]; }
  bool has_voronoi() const { return !vor_.empty(); }

  /// Each Delaunay edge once, as (i, j) with i < j, sorted.
  std::vector<std::array<int, 2>> edges() const;
  /// Finite Delaunay triangles, counter-clockwise, each once (empty when built without).
  const std::vector<std::array<int, 3>>& triangles() const { return tris_; }

  /// The site nearest to each query point (serial walks, each hinted by the previous answer;
  /// sort queries spatially for speed). Ties: any nearest site.
  std::vector<int> nearest(const std::vector<Vec2>& queries) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  bool with_triangles_ = true, with_voronoi_ = false;
  void build(const std::vector<Vec2>& sites);  // insertion + tables
  void tables();                               // adjacency, hull, Voronoi, triangles
  std::vector<int> ptr_, adj_;
  std::vector<char> hidden_, hull_;
  std::vector<Vec2> vor_;
  std::vector<std::array<int, 3>> tris_;
};

/// Indices [from, n) of `sites` in Hilbert-curve order (CGAL spatial sort; deterministic): the
/// free sites are renumbered in this order so that neighbours are close in memory.
std::vector<int> spatial_order(const std::vector<Vec2>& sites, int from = 0);

}  // namespace quadapt::lpcvt
