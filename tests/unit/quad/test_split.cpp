#include <doctest/doctest.h>

#include <cmath>

#include "quad/mesh_utils.hpp"
#include "quad/quality_summary.hpp"
#include "quad/subdivide.hpp"
#include "test_meshes.hpp"

using namespace quadapt;

TEST_CASE("split: each quad into 4, each triangle into 3, area and boundary kept") {
  Mesh m = make_perturbed_quads(5, 4, 0.2, 7);
  // turn one quad into two triangles to get a mixed mesh
  Cell q = m.cells[7];
  m.cells[7] = Cell{{q.v[0], q.v[1], q.v[2], -1}, 3};
  m.cells.push_back(Cell{{q.v[0], q.v[2], q.v[3], -1}, 3});
  const int nq = m.num_quads(), nt = m.num_triangles();
  Mesh s = split_to_all_quads(m);
  CHECK(s.all_quads());
  CHECK(s.num_cells() == 4 * nq + 3 * nt);
  CHECK(total_area(s) == doctest::Approx(total_area(m)).epsilon(1e-13));
  CHECK(s.boundary.size() == 2 * m.boundary.size());
  CHECK(s.groups.size() == m.groups.size());
  for (int g = 0; g < int(m.groups.size()); ++g) {
    double lin = 0, lout = 0;
    for (const auto& e : m.boundary)
      if (e.group == g) lin += (m.nodes[e.v[1]] - m.nodes[e.v[0]]).norm();
    for (const auto& e : s.boundary)
      if (e.group == g) lout += (s.nodes[e.v[1]] - s.nodes[e.v[0]]).norm();
    CHECK(lout == doctest::Approx(lin).epsilon(1e-13));
  }
  for (int c = 0; c < s.num_cells(); ++c) CHECK(cell_area(s, c) > 0);
  // conforming: Euler characteristic of a disk, V - E + F = 1
  auto fe = free_edges(s);
  long edges = (4L * s.num_cells() + long(fe.size())) / 2;
  CHECK(long(s.num_nodes()) - edges + s.num_cells() == 1);
  CHECK(fe.size() == s.boundary.size());
}

TEST_CASE("split: midpoints are exact and a square splits into squares") {
  Mesh m = make_structured_quads(1, 1);
  Mesh s = split_to_all_quads(m);
  CHECK(s.num_cells() == 4);
  for (int c = 0; c < 4; ++c) {
    CHECK(cell_area(s, c) == 0.25);
    CHECK(cell_min_angle_deg(s, c) == doctest::Approx(90));
  }
}

TEST_CASE("quality: angles, scaled Jacobian and shape tensor") {
  Mesh m;
  m.nodes = {{0, 0}, {2, 0}, {2, 1}, {0, 1}};
  m.cells = {Cell{{0, 1, 2, 3}, 4}};
  CHECK(cell_min_angle_deg(m, 0) == doctest::Approx(90));
  CHECK(cell_scaled_jacobian(m, 0) == doctest::Approx(1));
  auto J = cell_shape_tensor(m, 0);
  CHECK(J(0, 0) == doctest::Approx(4.0 / 12));
  CHECK(J(1, 1) == doctest::Approx(1.0 / 12));
  CHECK(J(0, 1) == doctest::Approx(0).epsilon(1e-14));
  auto s = stretch_summary(m);
  CHECK(s.mean_stretch == doctest::Approx(2));
  CHECK(s.mean_angle_deg == doctest::Approx(0).epsilon(1e-9));
  // a rotated 10:1 rectangle
  const double t = 30 * M_PI / 180;
  Vec2 u(std::cos(t), std::sin(t)), w(-std::sin(t), std::cos(t));
  m.nodes = {{0, 0}, 10 * u, 10 * u + w, w};
  s = stretch_summary(m);
  CHECK(s.mean_stretch == doctest::Approx(10));
  CHECK(s.mean_angle_deg == doctest::Approx(30));
  // an inverted (clockwise) quad has a negative scaled Jacobian
  m.cells[0].v = {0, 3, 2, 1};
  CHECK(cell_scaled_jacobian(m, 0) == doctest::Approx(-1));
  // non-convex quad: one reflex angle
  m.nodes = {{0, 0}, {2, 0}, {0.5, 0.5}, {0, 2}};
  m.cells[0].v = {0, 1, 2, 3};
  CHECK(cell_max_angle_deg(m, 0) > 180);
  CHECK(cell_scaled_jacobian(m, 0) < 0);
  // equilateral triangle scores 1
  m.nodes = {{0, 0}, {1, 0}, {0.5, std::sqrt(3.0) / 2}};
  m.cells[0] = Cell{{0, 1, 2, -1}, 3};
  CHECK(cell_scaled_jacobian(m, 0) == doctest::Approx(1));
  CHECK(cell_min_angle_deg(m, 0) == doctest::Approx(60));
}

TEST_CASE("parity fix: odd triangle count becomes even, boundary group kept") {
  Mesh m = testing::delaunay_unit_square(5, 30, 3, 1, 1, true);
  REQUIRE(m.num_cells() % 2 == 1);
  const double a = total_area(m);
  const size_t nb = m.boundary.size();
  CHECK(make_triangle_count_even(m));
  CHECK(m.num_cells() % 2 == 0);
  CHECK(total_area(m) == doctest::Approx(a).epsilon(1e-14));
  CHECK(m.boundary.size() == nb + 1);
  CHECK(!make_triangle_count_even(m));
  require_triangulation(m, "test");
}
