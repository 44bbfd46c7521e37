// Quality measures on meshes whose answers are known by hand.
#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <cmath>
#include <filesystem>
#include <random>

#include "io/msh.hpp"
#include "mesh/locate.hpp"
#include "quality/measures.hpp"
#include "quality/mesh_quality.hpp"

using namespace quadapt;

namespace {
Mesh one_cell(std::vector<Vec2> p) {
  Mesh m;
  m.nodes = p;
  Cell c;
  c.nv = static_cast<int>(p.size());
  for (int i = 0; i < c.nv; ++i) c.v[i] = i;
  m.cells.push_back(c);
  return m;
}

/// A frame: background grid over [x0,x1]^2 with the same M in every cell.
Mesh constant_frame(const Eigen::Matrix2d& M, double x0 = 0, double x1 = 1, int n = 3) {
  Mesh f = make_structured_quads(n, n, x0, x1, x0, x1);
  CellField v{"Vinv", 9, {}};
  for (int c = 0; c < f.num_cells(); ++c)
    for (double x : {M(0, 0), M(0, 1), 0.0, M(1, 0), M(1, 1), 0.0, 0.0, 0.0, 0.0}) v.values.push_back(x);
  f.set_field(v);
  return f;
}

Eigen::Matrix2d rotation(double deg) {
  const double a = deg * M_PI / 180;
  Eigen::Matrix2d R;
  R << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
  return R;
}
}  // namespace

TEST_CASE("square grid: all angles 90, scaled Jacobian 1") {
  Mesh m = make_structured_quads(8, 8);
  QualityReport r = measure_quality(m);
  CHECK(r.cells == 64);
  CHECK(r.quads == 64);
  CHECK(r.area == doctest::Approx(1.0).epsilon(1e-15));
  CHECK(r.physical.angle_min_deg == doctest::Approx(90).epsilon(1e-12));
  CHECK(r.physical.angle_max_deg == doctest::Approx(90).epsilon(1e-12));
  CHECK(r.physical.quad_angle_share_80_100 == 1.0);
  CHECK(r.physical.scaled_jacobian_min == doctest::Approx(1).epsilon(1e-15));
  CHECK(r.physical.scaled_jacobian_mean == doctest::Approx(1).epsilon(1e-15));
  CHECK(r.physical.edge_ratio_median == doctest::Approx(1).epsilon(1e-12));
  REQUIRE(r.groups.size() == 4);
  for (int e : r.group_edges) CHECK(e == 8);
  CHECK(!r.has_frame);
}

TEST_CASE("a rhombus of 60 and 120 degrees; triangles") {
  const double s = std::sqrt(3.0) / 2;
  Mesh rh = one_cell({{0, 0}, {1, 0}, {1.5, s}, {0.5, s}});
  ShapeStats st = shape_stats(rh);
  CHECK(st.angle_min_deg == doctest::Approx(60));
  CHECK(st.angle_max_deg == doctest::Approx(120));
  CHECK(st.angle_mean_deg == doctest::Approx(90));
  CHECK(st.quad_angle_share_80_100 == 0.0);
  CHECK(st.scaled_jacobian_min == doctest::Approx(s));
  CHECK(st.edge_ratio_median == doctest::Approx(1));
  // the longest edges (all equal): the first one, along x
  Mesh eq = one_cell({{0, 0}, {1, 0}, {0.5, s}});
  CHECK(shape_stats(eq).scaled_jacobian_min == doctest::Approx(1));
  Mesh right = one_cell({{0, 0}, {1, 0}, {0, 1}});
  CHECK(shape_stats(right).scaled_jacobian_min == doctest::Approx(std::sin(M_PI / 4) * 2 / std::sqrt(3.0)));
  CHECK(shape_stats(right).angle_max_deg == doctest::Approx(90));
  // a reflex (non-convex) quad: angle > 180, negative scaled Jacobian at that corner
  Mesh dart = one_cell({{0, 0}, {2, 1}, {0, 2}, {0.5, 1}});
  ShapeStats d = shape_stats(dart);
  CHECK(d.angle_max_deg > 180);
  CHECK(d.scaled_jacobian_min < 0);
}

TEST_CASE("metric space: a mesh of exact target elements measures as unit squares") {
  // Frame V = R(theta) diag(h1, h2): the target element has edges 2 h1 along v, 2 h2 along w.
  for (double theta : {0.0, 30.0}) {
    CAPTURE(theta);
    const double h1 = 1.0 / 8, h2 = 1.0 / 32;
    Eigen::Matrix2d V = rotation(theta) * Eigen::DiagonalMatrix<double, 2>(h1, h2);
    Eigen::Matrix2d M = V.inverse();
    // Mesh: the 4 x 16 grid of target elements, mapped by V from a grid of spacing 2.
    Mesh m = make_structured_quads(4, 16, 0, 8, 0, 32);
    for (Vec2& p : m.nodes) p = V * p;
    CHECK(total_area(m) == doctest::Approx(1.0));
    Frame frame = frame_from_mesh(constant_frame(M, -2, 2), "frame.msh", SizeConvention::Quadapt);
    QualityReport r = measure_quality(m, &frame, "frame.msh");
    REQUIRE(r.has_frame);
    CHECK(r.metric.angle_min_deg == doctest::Approx(90).epsilon(1e-9));
    CHECK(r.metric.angle_max_deg == doctest::Approx(90).epsilon(1e-9));
    CHECK(r.metric.scaled_jacobian_min == doctest::Approx(1).epsilon(1e-12));
    CHECK(r.metric.edge_ratio_median == doctest::Approx(1).epsilon(1e-9));
    CHECK(r.metric_edges.edges == 4 * 64);
    CHECK(r.metric_edges.min == doctest::Approx(1).epsilon(1e-12));
    CHECK(r.metric_edges.max == doctest::Approx(1).epsilon(1e-12));
    CHECK(r.metric_edges.share_in_range == 1.0);
    // physical: stretched 4:1 along theta, like the frame
    CHECK(r.physical.edge_ratio_median == doctest::Approx(h1 / h2));
    CHECK(r.physical.orientation_median_deg == doctest::Approx(theta));
    CHECK(r.frame.stretch_median == doctest::Approx(h1 / h2));
    CHECK(r.frame.orientation_median_deg == doctest::Approx(theta));
    CHECK(r.frame.cells_outside == 0);
    // continuous count over the background [-2,2]^2: 16 / (4 h1 h2)
    CHECK(r.frame.continuous_complexity == doctest::Approx(16.0 / (4 * h1 * h2)));
  }
}

TEST_CASE("continuous count equals the cell count when the mesh tiles the frame's domain") {
  Mesh m = make_structured_quads(4, 16);  // cells 1/4 x 1/16 = 2h1 x 2h2 with h1 = 1/8, h2 = 1/32
  Eigen::Matrix2d M = Eigen::DiagonalMatrix<double, 2>(8, 32);
  Frame frame = frame_from_mesh(constant_frame(M), "f", SizeConvention::Quadapt);
  QualityReport r = measure_quality(m, &frame, "f");
  CHECK(r.frame.continuous_complexity == doctest::Approx(64));
  CHECK(r.metric_edges.share_in_range == 1.0);
  // A reflected frame (det M < 0) is the same metric.
  Eigen::Matrix2d F = M;
  F.row(0) *= -1;
  Frame reflected = frame_from_mesh(constant_frame(F), "f", SizeConvention::Quadapt);
  QualityReport q = measure_quality(m, &reflected, "f");
  CHECK(q.metric.scaled_jacobian_min == doctest::Approx(1));
  CHECK(q.frame.continuous_complexity == doctest::Approx(64));
  // A mesh twice as fine in x has metric edge lengths 1/2 along x.
  Mesh fine = make_structured_quads(8, 16);
  QualityReport s = measure_quality(fine, &frame, "f");
  CHECK(s.metric_edges.min == doctest::Approx(0.5));
  CHECK(s.metric_edges.share_in_range == doctest::Approx(0.5));
  CHECK(s.metric.edge_ratio_median == doctest::Approx(2));
}

TEST_CASE("point location agrees with brute force") {
  Mesh m = make_perturbed_quads(12, 9, 0.3, 5);
  CellLocator loc(m);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-0.2, 1.2);
  int inside = 0;
  for (int k = 0; k < 2000; ++k) {
    Vec2 x(u(rng), u(rng));
    int c = loc.locate(x);
    bool in_square = x.x() > 0 && x.x() < 1 && x.y() > 0 && x.y() < 1;
    CHECK((c >= 0) == in_square);
    if (c < 0) {
      int n = loc.locate_or_nearest(x);
      REQUIRE(n >= 0);
      // nearest: a cell touching the boundary closest to x
      Vec2 clamp(std::clamp(x.x(), 0.0, 1.0), std::clamp(x.y(), 0.0, 1.0));
      CHECK(loc.locate_or_nearest(clamp) >= 0);
      continue;
    }
    ++inside;
    // x is inside cell c: its bilinear preimage lies in [-1,1]^2 (Newton)
    Vec2 xi(0, 0);
    for (int it = 0; it < 30; ++it) xi -= map_jacobian(m, c, xi.x(), xi.y()).inverse() * (map_to_physical(m, c, xi.x(), xi.y()) - x);
    CHECK(std::abs(xi.x()) <= 1 + 1e-9);
    CHECK(std::abs(xi.y()) <= 1 + 1e-9);
  }
  CHECK(inside > 800);  // about 2000 / 1.96
}

TEST_CASE("axial median handles the wrap at 0/180") {
  CHECK(axial_median_deg({179, 1, 2}) == doctest::Approx(1));
  CHECK(axial_median_deg({178, 179, 3}) == doctest::Approx(179));
  CHECK(axial_median_deg({30, 40, 50}) == doctest::Approx(40));
  CHECK(median({3, 1, 2, 10}) == doctest::Approx(2.5));
}

TEST_CASE("every PHiLiP fixture: measured as it is, and against its own frame") {
  namespace fs = std::filesystem;
  const std::string dir = std::string(QUADAPT_FIXTURES_DIR) + "/";
  int n = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.path().extension() != ".msh") continue;
    CAPTURE(e.path().filename().string());
    Mesh m = read_msh(e.path().string());
    QualityReport r = measure_quality(m);
    CHECK(r.physical.scaled_jacobian_min > 0);
    CHECK(r.area == doctest::Approx(1.0));
    if (e.path().filename().string().rfind("input_", 0) == 0) {
      const Frame fr = frame_from_mesh(m, e.path().string());  // no $FrameConvention: PHiLiP's sizes
      CHECK(fr.source == SizeConvention::Philip);
      QualityReport q = measure_quality(m, &fr, e.path().string());
      CHECK(q.frame.cells_outside == 0);
      CHECK(q.metric.scaled_jacobian_min > 0);  // reflections removed: cells keep orientation
      // PHiLiP normalises its step-3 frames to 1296 cells (integral of |det M_philip|)
      if (e.path().filename().string().find("_3.msh") != std::string::npos)
        CHECK(q.frame.continuous_complexity == doctest::Approx(1296).epsilon(1e-4));  // 6-digit file values
    }
    ++n;
  }
  CHECK(n == 16);
}

TEST_CASE("frame orientation: nearly isotropic cells have none, and the median turns with the frame") {
  // 3 x 3 background: 4 cells stretched 4:1 along theta, 5 isotropic (stretch 1 + 1e-9: the
  // SVD's long axis is arbitrary there). Turning the frame by 90 degrees turns the median by 90;
  // with the isotropic cells counted it did not (a review: 92.07 -> 4.34 instead of 2.07).
  for (double theta : {10.0, 100.0}) {
    CAPTURE(theta);
    const Eigen::Matrix2d Ma = (rotation(theta) * Eigen::DiagonalMatrix<double, 2>(0.2, 0.05)).inverse();
    const Eigen::Matrix2d Mi = (rotation(theta + 37) * Eigen::DiagonalMatrix<double, 2>(0.1, 0.1 * (1 - 1e-9))).inverse();
    Mesh f = constant_frame(Ma);
    CellField* v = f.cell_field("Vinv");
    for (int c : {0, 2, 4, 6, 8})
      for (int k : {0, 1, 3, 4}) (*v)(c, k) = Mi(k / 3, k % 3);
    Frame frame = frame_from_mesh(f, "f", SizeConvention::Quadapt);
    const Mesh m = make_structured_quads(4, 4);
    QualityReport r = measure_quality(m, &frame, "f");
    CHECK(r.frame.orientation_median_deg == doctest::Approx(theta).epsilon(1e-9));
  }
}
