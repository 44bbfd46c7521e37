#pragma once
// Triangulations for the quad module's unit tests (in memory, no file I/O).
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <map>
#include <random>

#include "mesh/mesh.hpp"

namespace quadapt::testing {

/// Delaunay triangulation of the unit square: n boundary segments per side (uniform), `inner`
/// random interior points (seeded), groups bottom/right/top/left. A convex domain with b
/// boundary and i interior points has 2i + b - 2 triangles: `odd` adds one boundary point (at
/// x = 0.5/n on the bottom side) to make that count odd.
inline Mesh delaunay_unit_square(int n, int inner, unsigned seed, double sx = 1.0, double sy = 1.0,
                                 bool odd = false) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K>;
  using Tds = CGAL::Triangulation_data_structure_2<Vb>;
  using DT = CGAL::Delaunay_triangulation_2<K, Tds>;
  Mesh m;
  m.groups = {{1, "bottom"}, {2, "right"}, {3, "top"}, {4, "left"}};
  // boundary nodes counter-clockwise
  for (int i = 0; i < n; ++i) {
    m.nodes.push_back({sx * double(i) / n, 0});
    if (odd && i == 0) m.nodes.push_back({sx * 0.5 / n, 0});
  }
  const int nbottom = n + (odd ? 1 : 0);
  for (int i = 0; i < n; ++i) m.nodes.push_back({sx, sy * double(i) / n});
  for (int i = 0; i < n; ++i) m.nodes.push_back({sx * double(n - i) / n, sy});
  for (int i = 0; i < n; ++i) m.nodes.push_back({0, sy * double(n - i) / n});
  const int nb = 3 * n + nbottom;
  for (int i = 0; i < nb; ++i) m.boundary.push_back({{i, (i + 1) % nb}, i < nbottom ? 0 : 1 + (i - nbottom) / n});
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(0.02, 0.98);
  for (int k = 0; k < inner; ++k) m.nodes.push_back({sx * U(rng), sy * U(rng)});
  std::vector<std::pair<K::Point_2, int>> pts;
  for (int i = 0; i < m.num_nodes(); ++i) pts.push_back({K::Point_2(m.nodes[i].x(), m.nodes[i].y()), i});
  DT dt;
  dt.insert(pts.begin(), pts.end());
  for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f) {
    Cell c;
    c.nv = 3;
    for (int i = 0; i < 3; ++i) c.v[i] = f->vertex(i)->info();
    m.cells.push_back(c);
  }
  return m;
}

/// Structured right triangles: an nx-by-ny grid, each square cut along a diagonal.
inline Mesh structured_triangles(int nx, int ny) {
  Mesh q = make_structured_quads(nx, ny);
  Mesh m = q;
  m.cells.clear();
  for (const auto& c : q.cells) {
    Cell a, b;
    a.nv = b.nv = 3;
    a.v = {c.v[0], c.v[1], c.v[2], -1};
    b.v = {c.v[0], c.v[2], c.v[3], -1};
    m.cells.push_back(a);
    m.cells.push_back(b);
  }
  return m;
}

}  // namespace quadapt::testing
