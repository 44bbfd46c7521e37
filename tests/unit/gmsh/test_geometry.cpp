// The Gmsh adapter's geometry (gmsh/geometry.hpp): named physical curves of a CAD file, exact
// points on them, the closest point, and the refusals (docs/curved.md, "Geometry").
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "core/error.hpp"
#include "gmsh/geometry.hpp"
#include "../worst.hpp"

using namespace quadapt;

namespace {
Vec2 c0_point(const BoundaryGeometry& g, int k) { return g.point(k, g.curves()[k].t0); }
}  // namespace

TEST_CASE("open_geometry: the cylinder's named curves, its circle exact, closest points by Newton") {
  const auto g = open_geometry(std::string(QUADAPT_SOURCE_DIR) + "/examples/geometry/cylinder.geo");
  CHECK(g->names() == std::vector<std::string>{"cylinder", "inlet", "outlet", "walls"});
  const auto cyl = g->curves_named("cylinder");
  REQUIRE(cyl.size() == 1);
  CHECK(g->curves()[cyl[0]].closed());
  CHECK(g->curves_named("walls").size() == 2);
  const auto& c = g->curves()[cyl[0]];
  double worst = 0, dworst = 0;
  for (int i = 0; i <= 50; ++i) {
    const double t = c.t0 + (c.t1 - c.t0) * i / 50;
    worst = quadapt_test::worst_of(worst, std::abs(g->point(cyl[0], t).norm() - 0.5));
    // c' against a central difference
    const double h = 1e-6;
    const Vec2 fd = (g->point(cyl[0], t + h) - g->point(cyl[0], t - h)) / (2 * h);
    dworst = quadapt_test::worst_of(dworst, (fd - g->derivative(cyl[0], t)).norm());
  }
  CHECK(worst < 1e-15);
  CHECK(dworst < 1e-8);
  const Vec2 p = g->closest_point(cyl, Vec2(1, 1));
  CHECK((p - Vec2(0.5 / std::sqrt(2.0), 0.5 / std::sqrt(2.0))).norm() < 1e-14);
  // on both sides of the closed curve's seam (its parameter's ends)
  const Vec2 s0 = c0_point(*g, cyl[0]);
  for (double a : {-1e-3, -1e-9, 0.0, 1e-9, 1e-3}) {
    const Vec2 x = s0.normalized() * std::cos(a) * 0.8 + Vec2(-s0.y(), s0.x()).normalized() * std::sin(a) * 0.8;
    CHECK((g->closest_point(cyl, x) - 0.5 * x.normalized()).norm() < 1e-14);
  }
  // the channel's corners are shared vertices of inlet and walls
  const Vec2 q = g->closest_point(g->curves_named("inlet"), Vec2(-3, -3));
  CHECK(q == Vec2(-1.5, -1.5));
}

TEST_CASE("open_geometry: a file Gmsh cannot read, and one without physical names, are refused naming it") {
  const std::string bad = "/tmp/quadapt_test_bad_geometry.geo", none = "/tmp/quadapt_test_noname_geometry.geo";
  std::ofstream(bad) << "Point(1) = {0, 0, 0\n";
  std::ofstream(none) << "Point(1) = {0, 0, 0};\nPoint(2) = {1, 0, 0};\nLine(1) = {1, 2};\n";
  CHECK_THROWS_WITH_AS(open_geometry(bad), doctest::Contains((bad + ": Gmsh cannot open it").c_str()), InputError);
  CHECK_THROWS_WITH_AS(open_geometry(none), doctest::Contains((none + ": no named physical curves").c_str()), InputError);
  std::remove(bad.c_str());
  std::remove(none.c_str());
}
