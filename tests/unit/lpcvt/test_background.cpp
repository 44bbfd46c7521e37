// Metric lookup, input validation and boundary equidistribution (thesis §4.1-4.2).
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "helpers.hpp"
#include "frame/frame.hpp"
#include "lpcvt/boundary_points.hpp"
#include "lpcvt/lpcvt.hpp"

using namespace lpcvt_test;

namespace {
// integral_0^1 |M(a + t(b-a)) (b-a)|_2 dt by composite Simpson with 2000 intervals
double fine_length(const AnalyticMetric& f, const Vec2& a, const Vec2& b) {
  const int n = 2000;
  double s = 0;
  for (int k = 0; k <= n; ++k) {
    double t = static_cast<double>(k) / n, w = (k == 0 || k == n) ? 1 : (k % 2 ? 4 : 2);
    s += w * (f.M(a + t * (b - a)) * (b - a)).norm();
  }
  return s / (3.0 * n);
}
}  // namespace

TEST_CASE("point location finds the containing cell, and nothing outside the domain") {
  Mesh m = l_shape();
  set_frame(m, 1, 1, 0);
  Background bg = Background::from_frame(m, 1.0, "mem");
  CHECK(bg.area() == doctest::Approx(3.0));
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.1, 2.1);
  int hint = -1;
  for (int k = 0; k < 2000; ++k) {
    Vec2 y(u(rng), u(rng));
    bool in = y.x() >= 0 && y.y() >= 0 && y.x() <= 2 && y.y() <= 2 && !(y.x() > 1 && y.y() > 1);
    int c = bg.locate(y, hint);
    CHECK((c >= 0) == in);
    if (c >= 0) {
      CHECK(in_convex_polygon(bg.cell(c).v, bg.cell(c).nv, y, 1e-12));
      hint = c;
    }
  }
  // node and edge points belong to the closed domain
  CHECK(bg.inside(Vec2(2, 0)));
  CHECK(bg.inside(Vec2(1, 1.5)));
  CHECK(bg.inside(Vec2(1.5, 1)));
}

TEST_CASE("frame validation: missing, non-finite or singular Vinv and inverted cells") {
  Mesh m = quadapt::make_structured_quads(2, 2);
  CHECK_THROWS_AS(Background::from_frame(m, 1.0, "f.msh"), quadapt::InputError);
  set_frame(m, 0.1, 0.2, 0.3);
  CHECK_NOTHROW(Background::from_frame(m, 1.0, "f.msh"));
  Mesh bad = m;
  bad.cell_field("Vinv")->values[9 + 1] = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH_AS(Background::from_frame(bad, 1.0, "f.msh"), doctest::Contains("non-finite"), quadapt::InputError);
  bad = m;
  for (int k : {0, 1, 3, 4}) bad.cell_field("Vinv")->values[18 + k] = 1.0;  // rank 1
  CHECK_THROWS_WITH_AS(Background::from_frame(bad, 1.0, "f.msh"), doctest::Contains("singular"), quadapt::InputError);
  bad = m;
  std::swap(bad.cells[0].v[1], bad.cells[0].v[3]);  // clockwise
  CHECK_THROWS_WITH_AS(Background::from_frame(bad, 1.0, "f.msh"), doctest::Contains("inverted"), quadapt::InputError);
  bad = m;
  bad.cell_field("Vinv")->values.pop_back();
  CHECK_THROWS_AS(Background::from_frame(bad, 1.0, "f.msh"), quadapt::InputError);
}

TEST_CASE("metric area = integral of det M_eff; the frame scale 1/4 gives 1/(16 h1 h2) points") {
  Mesh m = quadapt::make_structured_quads(3, 3);
  set_frame(m, 0.01, 0.04, 0.7);
  Background bg = Background::from_frame(m, 0.25, "mem");
  CHECK(bg.metric_area() == doctest::Approx(1.0 / (16 * 0.01 * 0.04)).epsilon(1e-12));
  auto f = std::make_shared<SaddleMetric>();
  Background sa = Background::analytic(saddle_square(4), f, 1.0);
  // integral of 1 + 4x^2 + 4y^2 over [-1.3,1.3]^2 = 6.76 + 8 * 2.6 * (2 * 1.3^3 / 3)
  CHECK(sa.metric_area() == doctest::Approx(6.76 + 8 * 2.6 * 2 * std::pow(1.3, 3) / 3).epsilon(1e-12));
}

TEST_CASE("boundary curves split at corners and keep their groups") {
  Mesh sq = quadapt::make_structured_quads(4, 4);
  set_frame(sq, 0.1, 0.1, 0);
  Background bg = Background::from_frame(sq, 1.0, "mem");
  auto curves = boundary_curves(bg);
  CHECK(curves.size() == 4);
  for (const auto& c : curves) {
    CHECK(c.nodes.size() == 5);
    CHECK(!c.closed);
  }
  Mesh L = l_shape();  // no groups: free edges, one group, six corners
  set_frame(L, 0.1, 0.1, 0);
  Background bl = Background::from_frame(L, 1.0, "mem");
  CHECK(boundary_curves(bl).size() == 6);
  Mesh H = square_with_hole();
  set_frame(H, 0.1, 0.1, 0);
  Background bh = Background::from_frame(H, 1.0, "mem");
  CHECK(boundary_curves(bh).size() == 8);
  CHECK(boundary_curves(bh, 120).size() == 2);  // no corners at 90 degrees: two closed loops
  for (const auto& c : boundary_curves(bh, 120)) CHECK(c.closed);
}

TEST_CASE("boundary points equidistribute the metric length (eqs. 4.2-4.7)") {
  auto f = std::make_shared<SaddleMetric>();
  Background bg = Background::analytic(saddle_square(16), f, 1.0);
  auto curves = boundary_curves(bg);
  BoundaryPoints b = mesh_boundary(bg, curves, 8);
  REQUIRE(curves.size() == 4);
  int seg = 0;
  for (size_t c = 0; c < curves.size(); ++c) {
    const Vec2 a = bg.mesh().nodes[curves[c].nodes.front()], z = bg.mesh().nodes[curves[c].nodes.back()];
    double exact = fine_length(*f, a, z);
    CHECK(b.curve_length[c] == doctest::Approx(exact).epsilon(1e-3));
    int n = b.curve_segments[c];
    CHECK(n == std::lround(exact));
    for (int k = 0; k < n; ++k, ++seg) {
      auto s = b.segments[seg];
      double l = fine_length(*f, b.points[s[0]], b.points[s[1]]);
      CHECK(l == doctest::Approx(exact / n).epsilon(2e-3));
    }
  }
  // corners are shared: 4 corners + interior points of the four sides
  int interior = 0;
  for (int n : b.curve_segments) interior += n - 1;
  CHECK(static_cast<int>(b.points.size()) == 4 + interior);
  // piecewise-constant metric: exact equidistribution of the piecewise-linear length
  Mesh m = quadapt::make_structured_quads(5, 1, 0, 1, 0, 0.2);
  set_frame(m, 0.05, 0.05, 0);
  Background bc = Background::from_frame(m, 1.0, "mem");
  BoundaryPoints bp = mesh_boundary(bc, boundary_curves(bc));
  for (auto s : bp.segments) CHECK((bp.points[s[0]] - bp.points[s[1]]).norm() == doctest::Approx(0.05).epsilon(1e-9));
}

TEST_CASE("attach_frame: the output's Vinv is the frame meshed, tagged as the quadapt convention") {
  quadapt::Frame f;
  f.mesh = quadapt::make_structured_quads(2, 2, 0, 1, 0, 1);
  f.M.assign(4, quadapt::frame_inverse(0.05, 4.0, 0.5));
  const Background bg = Background::from_frame(f, frame_metric_scale());
  Mesh m = quadapt::make_structured_quads(5, 3, 0, 1, 0, 1);
  attach_frame(m, bg);
  CHECK(m.frame_convention == "quadapt");
  // read back as any tool reads it: without the tag it would be PHiLiP's (M doubled, 4x the cells)
  const quadapt::Frame back = quadapt::frame_from_mesh(m, "mem");
  CHECK(back.source == quadapt::SizeConvention::Quadapt);
  for (int c = 0; c < back.num_cells(); ++c) CHECK((back.M[c] - f.M[0]).norm() <= 1e-14 * f.M[0].norm());
  CHECK(back.target_cells() == doctest::Approx(f.target_cells()).epsilon(1e-12));
}

TEST_CASE("point location on a strongly graded background: the first containing cell, as a full scan") {
  // 40 x 40 quads with the columns graded as t^4 towards x = 0: hundreds of cells fall in the
  // locator's first buckets (sub-grids there); the answer must be the first cell (index order)
  // that contains the point, as a scan of every cell gives, also on shared edges and nodes
  Mesh m = quadapt::make_structured_quads(40, 40);
  for (Vec2& p : m.nodes) p.x() = std::pow(p.x(), 4);
  set_frame(m, 1, 1, 0);
  Background bg = Background::from_frame(m, 1.0, "mem");
  auto scan = [&](const Vec2& y) {
    for (int c = 0; c < bg.num_cells(); ++c)
      if (bg.locate(y, c) == c) return c;  // locate's own containment test (hint = c)
    return -1;
  };
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0, 1), v(0, 1e-3);
  int checked = 0;
  for (int k = 0; k < 3000; ++k) {
    Vec2 y(k % 2 ? u(rng) : v(rng), u(rng));
    if (k % 3 == 0) y = m.nodes[k % m.num_nodes()];  // nodes: shared by up to four cells
    CHECK(bg.locate(y) == scan(y));
    ++checked;
  }
  CHECK(checked == 3000);
}

TEST_CASE("locate_near: the walk from a hint finds a containing cell, locate's off the edges, nothing outside") {
  // graded 30 x 30 quads (columns as t^3; cells of very different sizes on the walk) and the
  // L-shaped domain (the walk meets the re-entrant corner and the boundary)
  Mesh m = quadapt::make_structured_quads(30, 30);
  for (Vec2& p : m.nodes) p.x() = std::pow(p.x(), 3);
  set_frame(m, 1, 1, 0);
  Background bg = Background::from_frame(m, 1.0, "mem");
  Mesh l = l_shape();
  set_frame(l, 1, 1, 0);
  Background bl = Background::from_frame(l, 1.0, "mem");
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.05, 1.05);
  for (const Background* b : {&bg, &bl}) {
    const double s = b == &bl ? 2 : 1;
    std::uniform_int_distribution<int> cell(0, b->num_cells() - 1);
    int hint = -1, found = 0;
    for (int k = 0; k < 4000; ++k) {
      const Vec2 y(s * u(rng), s * u(rng));
      const int h = k % 2 ? hint : cell(rng);  // a near hint (the previous answer) or any cell
      const int c = b->locate_near(y, h), ref = b->locate(y);
      CHECK((c >= 0) == (ref >= 0));
      if (c < 0) continue;
      CHECK(in_convex_polygon(b->cell(c).v, b->cell(c).nv, y, 1e-12 * s));
      CHECK(c == ref);  // random points lie on no edge: the containing cell is unique
      hint = c;
      ++found;
    }
    CHECK(found > 2000);
  }
}

TEST_CASE("boundary points in the L_q metric length: one wall point per lattice row on oblique walls") {
  // a 5:1 frame at 45° on the unit square: every wall's metric tangent v = M tau is 11.3° off a
  // lattice axis, |v|_inf = 0.981 |v|_2 — rows of one family cross the wall |v|_inf times per
  // unit length; the Euclidean length asks for 2 % more wall points than rows
  const double h = 0.02, s = 5, th = M_PI / 4;
  Mesh m = quadapt::make_structured_quads(4, 4, 0, 1, 0, 1);
  set_frame(m, h * std::sqrt(s), h / std::sqrt(s), th);
  Background bg = Background::from_frame(m, 1.0, "mem");
  const auto curves = boundary_curves(bg);
  REQUIRE(curves.size() == 4);
  const BoundaryPoints b2 = mesh_boundary(bg, curves, 8, 2), b6 = mesh_boundary(bg, curves, 8, 6);
  const Mat2 M = bg.cell(0).M;
  for (size_t c = 0; c < curves.size(); ++c) {
    const Vec2 a = bg.mesh().nodes[curves[c].nodes.front()], z = bg.mesh().nodes[curves[c].nodes.back()];
    const Vec2 v = M * (z - a);
    // constant metric: the length is the norm of the mapped chord, for either q
    CHECK(b2.curve_length[c] == doctest::Approx(v.norm()).epsilon(1e-12));
    CHECK(b6.curve_length[c] == doctest::Approx(lq_norm(v, 6)).epsilon(1e-12));
    CHECK(b6.curve_segments[c] == std::lround(lq_norm(v, 6)));
    // q = 6 counts the rows of the dominant family to within 0.3 % (|v|_inf), the Euclidean length does not
    const double rows = std::max(std::abs(v.x()), std::abs(v.y()));
    CHECK(b6.curve_length[c] == doctest::Approx(rows).epsilon(3e-3));
    CHECK(b2.curve_length[c] > 1.015 * rows);
    CHECK(b6.curve_segments[c] < b2.curve_segments[c]);
  }
  // a wall along a lattice axis: both lengths agree bit for bit
  Mesh a = quadapt::make_structured_quads(4, 4, 0, 1, 0, 1);
  set_frame(a, h * std::sqrt(s), h / std::sqrt(s), 0);
  Background ba = Background::from_frame(a, 1.0, "mem");
  const auto ca = boundary_curves(ba);
  const BoundaryPoints a2 = mesh_boundary(ba, ca, 8, 2), a6 = mesh_boundary(ba, ca, 8, 6);
  CHECK(a2.points == a6.points);
  CHECK(lq_norm(Vec2(3, -4), 2) == 5);
  CHECK(lq_norm(Vec2(3, -4), 1) == doctest::Approx(7).epsilon(1e-15));
}

TEST_CASE("frames' default: the boundary is spaced in the energy's L_p norm; the analytic mode keeps eq. 4.2") {
  CHECK(LpcvtOptions::for_frame().boundary_norm == 0);  // 0 = the exponent p
  CHECK(LpcvtOptions::for_analytic().boundary_norm == 2);
}

TEST_CASE("lq_norm against hand values; the library refuses a norm that is not one") {
  CHECK(lq_norm(Vec2(3, 4), 6) == doctest::Approx(std::pow(4825.0, 1.0 / 6)).epsilon(1e-14));  // 3^6 + 4^6
  CHECK(lq_norm(Vec2(-1, 1), 1) == doctest::Approx(2).epsilon(1e-15));
  CHECK(lq_norm(Vec2(0, -2), 6) == 2);
  CHECK(lq_norm(Vec2(0, 0), 6) == 0);
  Mesh m = quadapt::make_structured_quads(2, 2, 0, 1, 0, 1);
  set_frame(m, 0.2, 0.2, 0);
  Background bg = Background::from_frame(m, 1.0, "mem");
  LpcvtOptions o = LpcvtOptions::for_frame();
  o.boundary_norm = 0.5;
  CHECK_THROWS_AS(run_lpcvt(bg, o), quadapt::InputError);
  o.boundary_norm = -1;
  CHECK_THROWS_AS(run_lpcvt(bg, o), quadapt::InputError);
  // 0 = the energy's exponent: the result reports the q it used
  o.boundary_norm = 0;
  o.p = 4;
  o.max_cycles = 1;
  o.lbfgs.max_iterations = 2;
  CHECK(run_lpcvt(bg, o).boundary_norm == 4);
}
