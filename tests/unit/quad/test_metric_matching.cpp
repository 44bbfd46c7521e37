// Metric matching (quad/metric_matching.hpp, issue #14): the quad quality in the metric and the
// maximum-weight pairing.
#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <vector>

#include "core/error.hpp"
#include "quad/metric_matching.hpp"

using namespace quadapt;

namespace {

Eigen::Matrix2d frame(double h1, double h2, double theta) {
  Eigen::Matrix2d M;
  const double c = std::cos(theta), s = std::sin(theta);
  M << c / h1, s / h1, -s / h2, c / h2;
  return M;
}

/// An nx x ny grid of the metric's unit squares (physical: rectangles h1 x h2 along theta),
/// each cut by a diagonal, alternating.
Mesh lattice(int nx, int ny, const Eigen::Matrix2d& M) {
  Mesh m;
  const Eigen::Matrix2d V = M.inverse();
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) m.nodes.push_back(V * Vec2(i, j));
  auto id = [&](int i, int j) { return j * (nx + 1) + i; };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      Cell t1, t2;
      t1.nv = t2.nv = 3;
      if ((i + j) % 2) {
        t1.v = {a, b, c, -1};
        t2.v = {a, c, d, -1};
      } else {
        t1.v = {a, b, d, -1};
        t2.v = {b, c, d, -1};
      }
      m.cells.push_back(t1);
      m.cells.push_back(t2);
    }
  return m;
}

}  // namespace

TEST_CASE("metric quad quality: 1 for the metric's square, 0.5 for 45 degrees, 0 when not convex") {
  const Eigen::Matrix2d M = frame(0.3, 0.01, 0.6), V = M.inverse();
  CHECK(metric_quad_quality(M, V * Vec2(0, 0), V * Vec2(1, 0), V * Vec2(1, 1), V * Vec2(0, 1)) ==
        doctest::Approx(1.0).epsilon(1e-12));
  CHECK(metric_quad_quality(M, V * Vec2(0, 0), V * Vec2(1, 0), V * Vec2(2, 1), V * Vec2(1, 1)) ==
        doctest::Approx(0.5).epsilon(1e-12));
  CHECK(metric_quad_quality(M, V * Vec2(0, 0), V * Vec2(1, 0), V * Vec2(0.2, 0.2), V * Vec2(0, 1)) == 0.0);
  // the same physical square measured in physical space is a 30:1 rectangle: also quality 1 there,
  // but the metric's square measured with the identity is not
  const Eigen::Matrix2d I = Eigen::Matrix2d::Identity();
  CHECK(metric_quad_quality(I, V * Vec2(0, 0), V * Vec2(1, 0), V * Vec2(2, 1), V * Vec2(1, 1)) < 0.2);
}

TEST_CASE("metric pairing of a rotated stretched lattice: every pair is a lattice square") {
  const Eigen::Matrix2d M = frame(0.2, 0.01, 0.5);
  Mesh tri = lattice(8, 6, M);
  std::vector<Eigen::Matrix2d> Ms(tri.num_cells(), M);
  MetricMatchingStats st;
  Mesh q = metric_pairing(tri, Ms, {}, &st);
  CHECK(st.quads == 48);
  CHECK(st.triangles == 0);
  CHECK(st.mean_quality == doctest::Approx(1.0).epsilon(1e-9));
  for (const Cell& c : q.cells) {
    REQUIRE(c.nv == 4);
    CHECK(metric_quad_quality(M, q.nodes[c.v[0]], q.nodes[c.v[1]], q.nodes[c.v[2]], q.nodes[c.v[3]]) ==
          doctest::Approx(1.0).epsilon(1e-9));
  }
}

TEST_CASE("metric pairing: an odd triangle count leaves one triangle, a sheared-only pair is refused") {
  const Eigen::Matrix2d M = frame(1, 1, 0);
  Mesh tri = lattice(3, 1, M);  // 6 triangles in a strip
  tri.cells.pop_back();         // 5: one must stay a triangle
  MetricMatchingStats st;
  Mesh q = metric_pairing(tri, {}, {}, &st);
  CHECK(st.quads == 2);
  CHECK(st.triangles == 1);
  CHECK(q.num_cells() == 3);
  // with min_quality above 0.5 a 45-degree pair is never made
  Mesh two;
  two.nodes = {Vec2(0, 0), Vec2(1, 0), Vec2(2, 1), Vec2(1, 1)};
  Cell a, b;
  a.nv = b.nv = 3;
  a.v = {0, 1, 3, -1};
  b.v = {1, 2, 3, -1};
  two.cells = {a, b};
  MetricMatchingOptions strict;
  strict.min_quality = 0.6;
  metric_pairing(two, {}, strict, &st);
  CHECK(st.quads == 0);
  metric_pairing(two, {}, {}, &st);
  CHECK(st.quads == 1);
}

TEST_CASE("metric pairing: a frame of the wrong size or a quad input is an InputError (a library caller's mistake)") {
  const Eigen::Matrix2d M = frame(1, 1, 0);
  const Mesh tri = lattice(3, 1, M);  // 6 triangles
  CHECK_THROWS_WITH_AS(metric_pairing(tri, std::vector<Eigen::Matrix2d>(3, M), {}), doctest::Contains("3 frame matrices for 6 triangles"),
                       InputError);
  Mesh quad = tri;
  quad.cells[0].nv = 4;
  quad.cells[0].v[3] = quad.cells[1].v[1];
  CHECK_THROWS_AS(metric_pairing(quad, {}, {}), InputError);
}

TEST_CASE("metric pairing: the interior bonus leaves the lone triangle at the wall") {
  // seven triangles: T0 = (0,0) (1,0) (0,1) in the middle, with no boundary edge; across each of
  // its edges a half-square Ti whose other half T(i+3) lies beyond (three squares, quality 1);
  // T0 with any Ti is a 45-degree parallelogram (quality 0.5). Odd count: one stays a triangle.
  Mesh m;
  m.nodes = {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1), Vec2(1, -1), Vec2(0, -1),
             Vec2(-1, 1), Vec2(-1, 0), Vec2(1, 2), Vec2(2, 1)};
  for (const std::array<int, 3>& t : std::vector<std::array<int, 3>>{
           {0, 1, 2}, {0, 3, 1}, {0, 2, 5}, {1, 7, 2}, {0, 4, 3}, {0, 5, 6}, {1, 8, 7}}) {
    Cell c;
    c.nv = 3;
    c.v = {t[0], t[1], t[2], -1};
    m.cells.push_back(c);
  }
  MetricMatchingStats st;
  MetricMatchingOptions o;
  // without the bonus: three squares (3 x 1.5) beat a parallelogram and two squares (1 + 2 x 1.5),
  // so the interior T0 is left
  o.interior_bonus = 0;
  Mesh q = metric_pairing(m, {}, o, &st);
  CHECK(st.quads == 3);
  CHECK(st.triangles == 1);
  CHECK(st.wall_triangles == 0);
  CHECK(st.mean_quality == doctest::Approx(1.0));
  // the parallelogram pays the bonus once (T0 is interior): it wins when 0.5 + bonus > 1
  o.interior_bonus = 0.4;
  metric_pairing(m, {}, o, &st);
  CHECK(st.wall_triangles == 0);
  o.interior_bonus = 0.6;
  q = metric_pairing(m, {}, o, &st);
  CHECK(st.quads == 3);
  CHECK(st.triangles == 1);
  CHECK(st.wall_triangles == 1);
  CHECK(st.mean_quality == doctest::Approx((0.5 + 1 + 1) / 3));
  REQUIRE(q.cells.back().nv == 3);
  bool t0_matched = false;
  for (const Cell& c : q.cells)
    if (c.nv == 4) {
      int hits = 0;
      for (int k = 0; k < 4; ++k) hits += c.v[k] == 0 || c.v[k] == 1 || c.v[k] == 2;
      t0_matched |= hits == 3;
    }
  CHECK(t0_matched);
}
