// Quality measures of curved cells (quality/measures.hpp curved_cell_shape), measured on the map:
// a polar annulus whose cells are the polar map's interpolants has right angles and scaled
// Jacobian ~1 on the map, while its vertex view (trapezoids) has 90 +- 22.5 degrees; arc
// lengths; a straight mesh stored at order q measures as the straight mesh; a linear map of the
// control points scales lengths and keeps angles.
#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <cmath>

#include "mesh/curved.hpp"
#include "quality/measures.hpp"
#include "quality/mesh_quality.hpp"

using namespace quadapt;

namespace {
// The annulus 1 <= r <= 2: nt cells around (angle 2 pi / nt each), 2 rings; the cells' control
// points are the polar map's images of the equispaced reference points (order q).
Mesh polar_annulus(int nt, int q) {
  Mesh m;
  const int nr = 2;
  auto node = [&](int i, int j) { return (i % nt) + nt * j; };
  for (int j = 0; j <= nr; ++j)
    for (int i = 0; i < nt; ++i) {
      const double r = 1 + double(j) / nr, t = 2 * M_PI * i / nt;
      m.nodes.emplace_back(r * std::cos(t), r * std::sin(t));
    }
  m.curved.order = q;
  for (int j = 0; j < nr; ++j)
    for (int i = 0; i < nt; ++i) {
      Cell c;
      c.nv = 4;
      c.v = {node(i, j), node(i, j + 1), node(i + 1, j + 1), node(i + 1, j)};  // xi: radius, eta: angle
      m.cells.push_back(c);
      for (int b = 0; b <= q; ++b)
        for (int a = 0; a <= q; ++a) {
          const bool corner = (a == 0 || a == q) && (b == 0 || b == q);
          const double r = 1 + (j + double(a) / q) / nr, t = 2 * M_PI * (i + double(b) / q) / nt;
          Vec2 x(r * std::cos(t), r * std::sin(t));
          if (corner) x = m.nodes[c.v[a == 0 ? (b == 0 ? 0 : 3) : (b == 0 ? 1 : 2)]];
          m.curved.points.push_back(x);
        }
    }
  return m;
}
}  // namespace

TEST_CASE("meshquality on curved cells: polar annulus measured on the map, not on its vertex view") {
  const int nt = 8, q = 4;
  const Mesh m = polar_annulus(nt, q);
  const QualityReport r = measure_quality(m);
  CHECK(r.geometric_order == q);
  CHECK(r.area == doctest::Approx(3 * M_PI).epsilon(1e-5));
  // tangents of the interpolated arcs and radial lines at the corners: 90 degrees to O(h^q)
  CHECK(std::abs(r.physical.angle_min_deg - 90) < 0.1);
  CHECK(std::abs(r.physical.angle_max_deg - 90) < 0.1);
  CHECK(r.physical.quad_angle_share_80_100 == 1.0);
  CHECK(r.physical.scaled_jacobian_min > 0.999);
  // the vertex view: isosceles trapezoids with 90 -+ 180/nt degrees
  Mesh straight = m;
  straight.curved = CurvedGeometry{};
  const QualityReport s = measure_quality(straight);
  CHECK(s.physical.angle_min_deg == doctest::Approx(90 - 180.0 / nt));
  CHECK(s.physical.angle_max_deg == doctest::Approx(90 + 180.0 / nt));
  CHECK(s.physical.scaled_jacobian_min == doctest::Approx(std::cos(M_PI / nt)));
  // arc lengths: outer arc of cell (i, ring 1) is 2 * 2 pi / nt (to the interpolation error)
  const int outer = nt;  // first cell of the outer ring; its local edge 1 lies on r = 2
  CHECK(curved_edge_length(m, outer, 1) == doctest::Approx(2 * 2 * M_PI / nt).epsilon(1e-5));
  CHECK(curved_edge_length(m, outer, 0) == doctest::Approx(0.5).epsilon(1e-12));
  const CellShape cs = curved_cell_shape(m, outer);
  CHECK(cs.edge_max == doctest::Approx(2 * 2 * M_PI / nt).epsilon(1e-5));
  CHECK(cs.edge_min == doctest::Approx(0.5).epsilon(1e-12));
  // a linear map of the control points: lengths scale, angles stay
  Eigen::Matrix2d M = 3 * Eigen::Matrix2d::Identity();
  const CellShape cm = curved_cell_shape(m, outer, &M);
  CHECK(cm.edge_max == doctest::Approx(3 * cs.edge_max));
  for (int i = 0; i < 4; ++i) CHECK(cm.angle_deg[i] == doctest::Approx(cs.angle_deg[i]));
  CHECK(cm.scaled_jacobian == doctest::Approx(cs.scaled_jacobian));
}

TEST_CASE("meshquality on curved cells: a straight mesh stored at order q measures as the straight mesh") {
  Mesh m = make_structured_quads(4, 3, 0, 2, 0, 1);
  for (Vec2& x : m.nodes) x = Vec2(x.x() + 0.1 * x.y() * x.y(), x.y() + 0.05 * x.x());  // a shear, not affine
  const QualityReport a = measure_quality(m);
  for (int q : {2, 3, 6}) {
    CAPTURE(q);
    Mesh c = m;
    elevate_geometric_order(c, q);
    const QualityReport b = measure_quality(c);
    CHECK(b.area == doctest::Approx(a.area).epsilon(1e-13));
    CHECK(b.physical.angle_min_deg == doctest::Approx(a.physical.angle_min_deg).epsilon(1e-12));
    CHECK(b.physical.angle_max_deg == doctest::Approx(a.physical.angle_max_deg).epsilon(1e-12));
    CHECK(b.physical.edge_ratio_median == doctest::Approx(a.physical.edge_ratio_median).epsilon(1e-12));
    CHECK(b.physical.orientation_median_deg == doctest::Approx(a.physical.orientation_median_deg).epsilon(1e-12));
    // sampled inside too: never above the corners' value
    CHECK(b.physical.scaled_jacobian_min <= a.physical.scaled_jacobian_min + 1e-12);
  }
}
