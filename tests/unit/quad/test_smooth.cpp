#include <doctest/doctest.h>

#include <cmath>

#include "quad/mesh_utils.hpp"
#include "quad/quality.hpp"
#include "quad/smooth.hpp"
#include "quad/split.hpp"
#include "test_meshes.hpp"

using namespace quadapt;

namespace {
double angle_deviation(const Mesh& m) {  // mean |angle - 90| over quad corners
  double s = 0;
  int n = 0;
  for (int c = 0; c < m.num_cells(); ++c)
    for (int k = 0; k < m.cells[c].nv; ++k, ++n) s += std::abs(corner_angle_deg(m, c, k) - 90);
  return s / n;
}
}  // namespace

TEST_CASE("smooth: a perturbed grid improves, min angle never drops, boundary fixed") {
  for (unsigned seed : {1u, 2u, 3u, 4u, 5u}) {
    Mesh m = make_perturbed_quads(12, 9, 0.35, seed);
    Mesh before = m;
    const auto q0 = quality_summary(m);
    SmoothOptions opt;
    opt.sweeps = 5;
    auto st = angle_smooth(m, opt);
    const auto q1 = quality_summary(m);
    CHECK(st.min_angle_before == doctest::Approx(q0.min_angle_deg));
    CHECK(q1.min_angle_deg >= q0.min_angle_deg);
    CHECK(q1.min_scaled_jacobian >= std::min(q0.min_scaled_jacobian, 0.5));
    CHECK(q1.inverted == 0);
    CHECK(angle_deviation(m) < angle_deviation(before));
    CHECK(st.moves_full + st.moves_reduced > 0);
    auto fixed = boundary_node_flags(before);
    for (int v = 0; v < m.num_nodes(); ++v)
      if (fixed[v]) CHECK(m.nodes[v] == before.nodes[v]);
    CHECK(total_area(m) == doctest::Approx(1.0).epsilon(1e-12));
  }
}

TEST_CASE("smooth: an anisotropic rectangular grid is a fixed point") {
  Mesh m = make_structured_quads(5, 40, 0, 1, 0, 0.5);  // 0.2 x 0.0125 rectangles, 16:1
  Mesh before = m;
  auto st = angle_smooth(m, {});
  for (int v = 0; v < m.num_nodes(); ++v) CHECK((m.nodes[v] - before.nodes[v]).norm() < 1e-12);
  CHECK(st.min_angle_after == doctest::Approx(90));
}

TEST_CASE("smooth: the split of a random Delaunay triangulation (mixed angles) never gets worse") {
  Mesh tri = testing::delaunay_unit_square(8, 150, 5);
  Mesh m = split_to_all_quads(tri);  // 3 quads per triangle: poor angles
  const auto q0 = quality_summary(m);
  Mesh before = m;
  SmoothOptions opt;
  for (int s = 0; s < 4; ++s) {  // one sweep at a time: monotone
    opt.sweeps = 1;
    const auto prev = quality_summary(m);
    angle_smooth(m, opt);
    CHECK(quality_summary(m).min_angle_deg >= prev.min_angle_deg);
    CHECK(quality_summary(m).min_scaled_jacobian >= std::min(prev.min_scaled_jacobian, 0.5));
    CHECK(quality_summary(m).inverted == 0);
  }
  const auto q1 = quality_summary(m);
  CHECK(q1.mean_cell_min_angle_deg > q0.mean_cell_min_angle_deg);
  CHECK(angle_deviation(m) < angle_deviation(before));
}

TEST_CASE("smooth: mixed triangle/quad mesh keeps validity") {
  Mesh m = make_perturbed_quads(8, 8, 0.3, 9);
  for (int c : {10, 20, 30}) {  // split three quads into triangles
    Cell q = m.cells[c];
    m.cells[c] = Cell{{q.v[0], q.v[1], q.v[2], -1}, 3};
    m.cells.push_back(Cell{{q.v[0], q.v[2], q.v[3], -1}, 3});
  }
  const double a0 = quality_summary(m).min_angle_deg;
  angle_smooth(m, {});
  const auto q1 = quality_summary(m);
  CHECK(q1.min_angle_deg >= a0);
  CHECK(q1.inverted == 0);
}
