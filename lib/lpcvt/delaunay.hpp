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
  explicit DelaunayGraph(const std::vector<Vec2>& sites);
  ~DelaunayGraph();
  DelaunayGraph(DelaunayGraph&&) noexcept;
  DelaunayGraph& operator=(DelaunayGraph&&) noexcept;

  int num_sites() const { return static_cast<int>(ptr_.size()) - 1; }
  /// Finite Delaunay neighbours of site i, counter-clockwise: [nbr_begin(i), nbr_end(i)).
  const int* nbr_begin(int i) const { return adj_.data() + ptr_[i]; }
  const int* nbr_end(int i) const { return adj_.data() + ptr_[i + 1]; }
  int degree(int i) const { return ptr_[i + 1] - ptr_[i]; }
  bool hidden(int i) const { return hidden_[i] != 0; }

  /// Each Delaunay edge once, as (i, j) with i < j, sorted.
  std::vector<std::array<int, 2>> edges() const;
  /// Finite Delaunay triangles, counter-clockwise, each once.
  const std::vector<std::array<int, 3>>& triangles() const { return tris_; }

  /// The site nearest to each query point (serial walks, each hinted by the previous answer;
  /// sort queries spatially for speed). Ties: any nearest site.
  std::vector<int> nearest(const std::vector<Vec2>& queries) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::vector<int> ptr_, adj_;
  std::vector<char> hidden_;
  std::vector<std::array<int, 3>> tris_;
};

}  // namespace quadapt::lpcvt
