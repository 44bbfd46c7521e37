// Curving a straight-sided mesh onto the true geometry (mesh/geometry.hpp, mesh/snap.hpp,
// mesh/curve_boundary.hpp; docs/curved.md): the closest point, snapping, and the curved cells'
// area against the polynomial region of the same boundary nodes (curved_disk, whose area
// test_curved.cpp checks against the boundary integral 1/2 of the closed integral of x dy - y dx).
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>

#include "core/error.hpp"
#include "curved_disk.hpp"
#include "mesh/curve_boundary.hpp"
#include "mesh/curved.hpp"
#include "mesh/validate.hpp"
#include "fem/basis.hpp"
#include <functional>
#include "refine/refine.hpp"
#include "../worst.hpp"

using namespace quadapt;
using curvedtest::curved_disk;

namespace {

FunctionGeometry circle_geometry(double R = 1.0) {
  return FunctionGeometry("circle.geo", {FunctionGeometry::circle("circle", Vec2(0, 0), R)});
}

// Largest | |x| - R | over every control point of the boundary edges (local edge 1 of the disk's
// cells); NaN unless every boundary edge was found there (none found returned 0 and passed: a
// test audit, session 38).
double boundary_distance(const Mesh& m, double R = 1.0) {
  const int q = m.geometric_order();
  double d = 0;
  size_t found = 0;
  for (int c = 0; c < m.num_cells(); ++c)
    for (const BoundaryEdge& be : m.boundary)
      if (be.v[0] == m.cells[c].v[1] && be.v[1] == m.cells[c].v[2]) {
        ++found;
        for (int k : edge_control_points(q, 1))
          d = quadapt_test::worst_of(d, std::abs(m.cell_points(c)[k].norm() - R));
      }
  return found == m.boundary.size() && found > 0 ? d : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

TEST_CASE("geometry: closest point on a circle by Newton, to rounding") {
  const FunctionGeometry g = circle_geometry(0.5);
  CHECK(g.curves()[0].closed());
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-2, 2);
  double worst = 0;
  for (int i = 0; i < 200; ++i) {
    const Vec2 x(u(rng), u(rng));
    if (x.norm() < 1e-3) continue;
    const Vec2 p = g.closest_point({0}, x);
    worst = quadapt_test::worst_of(worst, (p - 0.5 * x.normalized()).norm());
  }
  CHECK(worst < 1e-14);
}

TEST_CASE("snap: chord midpoints of a refined disk go onto the circle; each split parent's centre follows by half") {
  const FunctionGeometry g = circle_geometry();
  RefineOptions opt;
  Mesh m = refine_mesh(curved_disk(2, 1), opt);
  double before = 0;
  for (const auto& e : m.boundary) before = std::max(before, std::abs(m.nodes[e.v[0]].norm() - 1));
  CHECK(before > 1e-3);  // the midpoints lie on the chords
  const Mesh m0 = m;
  const SnapStats s = snap_to_geometry(m, g, "disk.msh");
  CHECK(s.moved >= 8);  // the 8 midpoints (old nodes may move by rounding)
  CHECK(s.max_move == doctest::Approx(1 - std::cos(M_PI / 8)).epsilon(1e-6));
  CHECK(s.max_distance < 1e-15);
  for (const auto& e : m.boundary) CHECK(std::abs(m.nodes[e.v[0]].norm() - 1) < 1e-15);
  // the parent's Coons map at its centre: half of the mid-edge node's move; nothing else moves
  const double half = 0.5 * (1 - std::cos(M_PI / 8));
  CHECK(s.max_interior_move == doctest::Approx(half).epsilon(1e-6));
  int centres = 0;
  for (int v = 0; v < m.num_nodes(); ++v) {
    if (m.nodes[v].norm() > 1 - 1e-15) continue;  // boundary
    const double moved = (m.nodes[v] - m0.nodes[v]).norm();
    if (moved < 1e-12) continue;  // old boundary nodes move by rounding
    ++centres;
    CHECK(moved == doctest::Approx(half).epsilon(1e-6));
  }
  CHECK(centres == 8);
}

TEST_CASE("curve_boundary_cells: disk at q = 2 to 6: boundary nodes on the circle to 1e-12, area of the polynomial region to 1e-12") {
  const FunctionGeometry g = circle_geometry();
  for (int q : {2, 3, 4, 5, 6})
    for (int n : {1, 2, 4}) {
      CAPTURE(q);
      CAPTURE(n);
      Mesh m = curved_disk(n, 1);
      const CurveStats st = curve_boundary_cells(m, g, q, "disk.msh");
      CHECK(m.geometric_order() == q);
      CHECK(st.boundary_edges == 4 * n);
      CHECK(boundary_distance(m) < 1e-12);
      CHECK(st.max_distance < 1e-12);
      // the same boundary nodes (equal angles) as the exact patch map's disk: the same region
      const double A = total_area(m), A_ref = total_area(curved_disk(n, q));
      CHECK(std::abs(A - A_ref) < 1e-12);
      CHECK(std::abs(A - M_PI) < 0.05);  // and a disk
      CHECK(st.min_scaled_jacobian > 0.2);
      CHECK(st.min_scaled_jacobian == doctest::Approx(min_scaled_jacobian(m).min));
      ValidateOptions v;
      v.allow_curved = true;
      CHECK_NOTHROW(validate_mesh(m, "disk.msh", v));
    }
}

// Integral of a smooth f over the boundary edges (local edge 1 of the disk's ring cells) of m.
double boundary_integral(const Mesh& m, const std::function<double(const Vec2&)>& f) {
  static const Rule1D rule = gauss_legendre(12);
  double s = 0;
  for (int c = 0; c < m.num_cells(); ++c)
    for (const BoundaryEdge& be : m.boundary)
      if (be.v[0] == m.cells[c].v[1] && be.v[1] == m.cells[c].v[2]) {
        const CellMap G(m, c);
        for (size_t k = 0; k < rule.x.size(); ++k) {
          Vec2 x, n;
          s += 0.5 * rule.w[k] * edge_geometry(G, 1, 0.5 * (rule.x[k] + 1), x, n) * f(x);
        }
      }
  return s;
}

TEST_CASE("curve_boundary_cells: area-matched edge nodes make boundary integrals converge at >= 2q for odd q") {
  // The curve r(t) = 1 + e cos 3t (e = 0.2; curvature varies from -0.1 to 3.1 — not a conic, whose
  // affine image of a circle would behave as the circle): the disk mesh mapped by
  // x (1 + e (x^3 - 3 x y^2)), which is r(t) on the unit circle. f smooth; reference by the
  // periodic trapezoidal rule (exact to rounding). Measured |error| on n = 2, 4, 8, 16 (8n edges):
  // q = 3 equal 1.0e-3, 7.9e-5, 5.2e-6, 3.3e-7 (rates 3.67, 3.92, 3.98), area 6.4e-5, 3.6e-7,
  // 5.1e-9, 8.1e-11 (7.47, 6.15, 5.98); q = 5 equal 5.7e-6, 2.2e-7, 3.9e-9, 6.4e-11, area
  // 1.6e-6, 4.7e-9, 2.7e-11, 3.1e-13 (the last near rounding). (With e = 0.2 the curve has
  // inflection points, where moving nodes along the curve hardly changes the area: the stretch
  // grows, and q = 3 gains a factor 32 at n = 8 but converges at 4.7 there.)
  const double E = 0.05;
  auto f = [](const Vec2& x) { return std::exp(0.3 * x.x()) * (1 + 0.5 * std::sin(x.x() + 0.7 * x.y())) + x.x() * x.x() * x.y(); };
  double exact = 0;
  for (int k = 0; k < 4096; ++k) {
    const double t = 2 * M_PI * k / 4096, r = 1 + E * std::cos(3 * t), dr = -3 * E * std::sin(3 * t);
    exact += f(r * Vec2(std::cos(t), std::sin(t))) * std::hypot(r, dr);
  }
  exact *= 2 * M_PI / 4096;
  auto c = [&](double t) -> Vec2 { return (1 + E * std::cos(3 * t)) * Vec2(std::cos(t), std::sin(t)); };
  auto dc = [&](double t) -> Vec2 {
    return -3 * E * std::sin(3 * t) * Vec2(std::cos(t), std::sin(t)) + (1 + E * std::cos(3 * t)) * Vec2(-std::sin(t), std::cos(t));
  };
  auto ddc = [&](double t) -> Vec2 {
    const Vec2 u(std::cos(t), std::sin(t)), v(-std::sin(t), std::cos(t));
    return -9 * E * std::cos(3 * t) * u - 6 * E * std::sin(3 * t) * v - (1 + E * std::cos(3 * t)) * u;
  };
  const FunctionGeometry g("star.geo", {FunctionGeometry::Curve{"circle", 0, 2 * M_PI, c, dc, ddc}});
  auto star = [&](int n) {
    Mesh m = curved_disk(n, 1);
    for (Vec2& x : m.nodes) x *= 1 + E * (x.x() * x.x() * x.x() - 3 * x.x() * x.y() * x.y());
    return m;
  };
  for (int q : {2, 3, 4, 5}) {
    double prev_equal = 0, prev_area = 0;
    for (int n : {2, 4, 8, 16}) {
      CAPTURE(q);
      CAPTURE(n);
      Mesh me = star(n), ma = star(n);
      curve_boundary_cells(me, g, q, "star.msh");
      const CurveStats st = curve_boundary_cells(ma, g, q, "star.msh", false, BoundaryNodes::Area);
      CHECK(st.max_distance < 1e-12);  // the nodes stay on the curve
      const double ee = std::abs(boundary_integral(me, f) - exact), ea = std::abs(boundary_integral(ma, f) - exact);
      if (q % 2 == 0) {
        CHECK(ma.curved.points == me.curved.points);  // even q: nothing to gain, equal steps
        CHECK(st.max_stretch == 0);
      }
      if (q == 3 && n == 16) {
        CHECK(std::log2(prev_area / ea) > 5.7);   // 2q
        CHECK(std::log2(prev_equal / ee) < 4.2);  // q + 1
      }
      if (q == 5 && n >= 4) CHECK(ea < 0.05 * ee);
      prev_equal = ee;
      prev_area = ea;
    }
  }
}

TEST_CASE("curve_boundary_cells: a refined disk (midpoints snapped first) equals the finer disk's region") {
  const FunctionGeometry g = circle_geometry();
  RefineOptions opt;
  Mesh m = refine_mesh(curved_disk(2, 1), opt);
  curve_boundary_cells(m, g, 3, "disk.msh");
  CHECK(boundary_distance(m) < 1e-12);
  CHECK(std::abs(total_area(m) - total_area(curved_disk(4, 3))) < 1e-12);
}

TEST_CASE("curve_boundary_cells: a cell thinner than its curved edge's bulge is refused, naming it") {
  // one cell [0,1] x [0,0.1] whose bottom edge is an arc bulging 0.207 into it
  const double c = -0.5, r = std::sqrt(0.25 + c * c);
  FunctionGeometry::Curve arc;
  arc.name = "bottom";
  const double a0 = std::atan2(-c, -0.5), a1 = std::atan2(-c, 0.5);  // from (0,0) to (1,0) over the top
  arc.t0 = 0;
  arc.t1 = 1;
  arc.c = [=](double t) { const double a = a0 + t * (a1 - a0); return Vec2(0.5 + r * std::cos(a), c + r * std::sin(a)); };
  arc.dc = [=](double t) { const double a = a0 + t * (a1 - a0); return Vec2(-r * std::sin(a) * (a1 - a0), r * std::cos(a) * (a1 - a0)); };
  arc.ddc = [=](double t) { const double a = a0 + t * (a1 - a0); return Vec2(-r * std::cos(a) * (a1 - a0) * (a1 - a0), -r * std::sin(a) * (a1 - a0) * (a1 - a0)); };
  const FunctionGeometry g("thin.geo", {arc, FunctionGeometry::segment("right", {1, 0}, {1, 0.1}),
                                       FunctionGeometry::segment("top", {1, 0.1}, {0, 0.1}),
                                       FunctionGeometry::segment("left", {0, 0.1}, {0, 0})});
  CHECK((g.point(0, 0.5) - Vec2(0.5, c + r)).norm() < 1e-15);
  Mesh m = make_structured_quads(1, 1, 0, 1, 0, 0.1);
  Mesh copy = m;
  CHECK_NOTHROW(curve_boundary_cells(copy, g, 1, "thin.msh"));  // q = 1: the vertices are on the curves
  try {
    curve_boundary_cells(m, g, 2, "thin.msh");
    FAIL("no error");
  } catch (const NumericalError& e) {
    CHECK(std::string(e.what()).find("thin.msh: curving the boundary cells folds cell 1 (centroid (0.5, 0.05))") != std::string::npos);
  }
}

TEST_CASE("snap: a boundary name the geometry does not have, and a mesh of another domain, are refused") {
  const FunctionGeometry g = circle_geometry();
  Mesh sq = make_structured_quads(2, 2);
  CHECK_THROWS_WITH_AS(snap_to_geometry(sq, g, "sq.msh"),
                       doctest::Contains("sq.msh: boundary 'bottom' is not a physical curve of circle.geo"), InputError);
  Mesh big = curved_disk(1, 1, 5.0);  // a disk of radius 5: far from the unit circle
  CHECK_THROWS_WITH_AS(snap_to_geometry(big, g, "big.msh"), doctest::Contains("is not a mesh of that geometry"), InputError);
}
