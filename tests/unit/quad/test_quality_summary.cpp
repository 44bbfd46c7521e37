#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "mesh/mesh.hpp"
#include "quad/quality_summary.hpp"

using namespace quadapt;

// Every figure of the quality summary the quad tools report (recombine, quadsmooth, bamgquad),
// on a mesh whose angles and Jacobians are known in closed form: a 6 x 4 grid of 0.5-cells on
// [0, 3] x [0, 2], the rows y in [1, 1.5] sheared to parallelograms with corners a1 = 25 and
// 155 deg, the rows y in [1.5, 2] to a2 = 40 and 140 deg (scaled Jacobian sin a at every corner
// of such a cell); the lower 12 cells stay squares (90 deg, 1). The shear keeps every area. a2
// lies between 30 and 60 deg so that the below-30 count tells 30 from another threshold.
TEST_CASE("quality_summary: angles, below-30 count, scaled Jacobians and area of a sheared grid") {
  const double pi = std::acos(-1.0), a1 = 25.0, a2 = 40.0, r1 = a1 * pi / 180, r2 = a2 * pi / 180;
  Mesh m = make_structured_quads(6, 4, 0, 3, 0, 2);
  for (auto& x : m.nodes)
    if (x.y() > 1) x.x() += (std::min(x.y(), 1.5) - 1) / std::tan(r1) + std::max(x.y() - 1.5, 0.0) / std::tan(r2);
  const QualitySummary q = quality_summary(m);
  CHECK(q.cells == 24);
  CHECK(q.quads == 24);
  CHECK(q.triangles == 0);
  CHECK(q.min_angle_deg == doctest::Approx(a1).epsilon(1e-12));
  CHECK(q.max_angle_deg == doctest::Approx(180 - a1).epsilon(1e-12));
  CHECK(q.mean_angle_deg == doctest::Approx(90).epsilon(1e-12));
  CHECK(q.mean_cell_min_angle_deg == doctest::Approx((12 * 90 + 6 * a1 + 6 * a2) / 24).epsilon(1e-12));
  CHECK(q.angles_below_30 == 2 * 6);  // the two 25-degree corners of each cell of row 3
  CHECK(q.min_scaled_jacobian == doctest::Approx(std::sin(r1)).epsilon(1e-12));
  CHECK(q.mean_scaled_jacobian == doctest::Approx((12 + 6 * std::sin(r1) + 6 * std::sin(r2)) / 24).epsilon(1e-12));
  CHECK(q.inverted == 0);
  CHECK(q.area == doctest::Approx(6.0).epsilon(1e-12));

  // one cell turned clockwise: inverted, its scaled Jacobian negative, the area down by 2 cells
  std::swap(m.cells[0].v[1], m.cells[0].v[3]);
  const QualitySummary r = quality_summary(m);
  CHECK(r.inverted == 1);
  CHECK(r.min_scaled_jacobian == doctest::Approx(-1).epsilon(1e-12));
  CHECK(r.area == doctest::Approx(6.0 - 2 * 0.25).epsilon(1e-12));
}
