// lib/io/vtu (VTK Lagrange node order) and lib/io/gmsh_options (the .msh.opt text).
#include <doctest/doctest.h>

#include <set>
#include <sstream>

#include "io/gmsh_options.hpp"
#include "io/vtu.hpp"

using namespace quadapt;

TEST_CASE("VTK Lagrange quad order: a permutation, corners first, edges in increasing parametric order") {
  for (int q = 1; q <= 8; ++q) {
    const int n = q + 1;
    std::set<int> seen;
    for (int k = 0; k < n * n; ++k) seen.insert(vtk_lagrange_quad_node(q, k));
    CHECK(static_cast<int>(seen.size()) == n * n);
    CHECK(*seen.begin() == 0);
    CHECK(*seen.rbegin() == n * n - 1);
    // corners (0,0) (q,0) (q,q) (0,q)
    CHECK(vtk_lagrange_quad_node(q, 0) == 0);
    CHECK(vtk_lagrange_quad_node(q, 1) == q);
    CHECK(vtk_lagrange_quad_node(q, 2) == q + n * q);
    CHECK(vtk_lagrange_quad_node(q, 3) == n * q);
  }
  // q = 3 written out (vtkHigherOrderQuadrilateral::PointIndexFromIJK): the top and left edges
  // run in increasing a and b, not counter-clockwise
  const int expect[16] = {0, 3, 15, 12, 1, 2, 7, 11, 13, 14, 4, 8, 5, 6, 9, 10};
  for (int k = 0; k < 16; ++k) CHECK(vtk_lagrange_quad_node(3, k) == expect[k]);
}

TEST_CASE("gmsh .opt: one block per DG view at its view index, level 2^L >= 2p, capped by cell count") {
  Mesh m = make_structured_quads(4, 4);
  CHECK(gmsh_view_options(m).empty());
  CellField h{"h", 1, std::vector<double>(16, 1.0)};
  m.set_field(h);
  CellNodeField u{"u", 1, 9, 2, std::vector<double>(16 * 9, 0.0)};
  m.set_field(u);
  std::string t = gmsh_view_options(m);
  // the file's second of two views, counted from the last view Gmsh holds (other files may be open)
  CHECK(t.find("View[PostProcessing.NbViews - 1].AdaptVisualizationGrid = 1;") != std::string::npos);
  CHECK(t.find("View[PostProcessing.NbViews - 1].MaxRecursionLevel = 2;") != std::string::npos);  // p = 2: 2^2 >= 4
  CHECK(t.find("NbViews - 2") == std::string::npos);  // the cell field keeps Gmsh's defaults
  CHECK(t.find("View[0]") == std::string::npos);
  Mesh big = make_structured_quads(300, 300);  // 9e4 cells: 4^L <= 44 -> L = 2 even for p = 8
  CellNodeField u8{"u", 1, 81, 8, std::vector<double>(90000 * 81, 0.0)};
  big.set_field(u8);
  t = gmsh_view_options(big);
  CHECK(t.find("View[PostProcessing.NbViews - 1].MaxRecursionLevel = 2;") != std::string::npos);
}
