// lib/frame: the frame contract (conventions and their tag, reflections, validation, target
// cell count, rescale, sampling).
#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "core/error.hpp"
#include "frame/frame.hpp"
#include "io/msh.hpp"

using namespace quadapt;

namespace {
// n x n background of [0,1]^2 with one M everywhere (no tag: as built in memory).
Mesh untagged(int n, const Mat2& M) {
  Mesh m = make_structured_quads(n, n);
  CellField v{"Vinv", 9, {}};
  for (int c = 0; c < m.num_cells(); ++c)
    for (double x : vinv_components(M)) v.values.push_back(x);
  m.set_field(v);
  return m;
}
Mesh roundtrip(const Mesh& m) {
  std::stringstream s;
  write_msh(m, s);
  return read_msh(s, "mem.msh");
}
}  // namespace

TEST_CASE("frame_inverse: M V = I for V = R(theta) diag(h1, h2), det M = 1/h^2") {
  const double h = 0.1, rho = 4, th = 0.3;
  const Mat2 M = frame_inverse(h, rho, th);
  Mat2 R;
  R << std::cos(th), -std::sin(th), std::sin(th), std::cos(th);
  const Mat2 V = R * Eigen::Vector2d(h * 2, h / 2).asDiagonal();
  CHECK((M * V - Mat2::Identity()).norm() < 1e-12);
  CHECK(M.determinant() == doctest::Approx(1 / (h * h)));
  auto [v, w] = frame_axes(M);
  CHECK((v - V.col(0)).norm() < 1e-12);
  CHECK((w - V.col(1)).norm() < 1e-12);
}

TEST_CASE("quadapt writes its convention; a file without one is read as PHiLiP's") {
  const Mat2 M = Eigen::Vector2d(8, 32).asDiagonal();  // target cells 1/4 x 1/16
  Mesh m = make_structured_quads(4, 4);
  set_frame_field(m, std::vector<Mat2>(m.num_cells(), M));
  const Mesh back = roundtrip(m);
  CHECK(back.frame_convention == "quadapt");
  const Frame q = frame_from_mesh(back, "q.msh");
  CHECK(q.source == SizeConvention::Quadapt);
  CHECK(q.M[0] == M);
  CHECK(q.target_cells() == doctest::Approx(64));  // the unit square in 1/4 x 1/16 cells

  // The same numbers without the section: PHiLiP's full-edge sizes, four times the cells.
  const Mesh bare = roundtrip(untagged(4, M));
  CHECK(bare.frame_convention.empty());
  const Frame p = frame_from_mesh(bare, "p.msh");
  CHECK(p.source == SizeConvention::Philip);
  CHECK(p.M[0] == 2 * M);
  CHECK(p.target_cells() == doctest::Approx(256));
  // An explicit convention overrides the file's.
  CHECK(frame_from_mesh(bare, "p.msh", SizeConvention::Quadapt).target_cells() == doctest::Approx(64));
  // Clearing the fields clears the statement with them.
  Mesh cleared = back;
  cleared.clear_fields();
  CHECK(cleared.frame_convention.empty());
}

TEST_CASE("unknown convention words and bad frames are InputErrors naming the file") {
  Mesh m = untagged(2, Mat2::Identity());
  m.frame_convention = "metres";
  CHECK_THROWS_WITH_AS(frame_from_mesh(m, "f.msh"), doctest::Contains("f.msh: unknown frame size convention 'metres'"),
                       InputError);
  Mesh s = untagged(2, Mat2::Identity());
  s.cell_field("Vinv")->values[9 + 4] = 0;  // rank 1
  s.cell_field("Vinv")->values[9 + 0] = 0;
  CHECK_THROWS_WITH_AS(frame_from_mesh(s, "f.msh"), doctest::Contains("singular"), InputError);
  Mesh n = untagged(2, Mat2::Identity());
  n.cell_field("Vinv")->values[0] = NAN;
  CHECK_THROWS_WITH_AS(frame_from_mesh(n, "f.msh"), doctest::Contains("non-finite"), InputError);
  Mesh none = make_structured_quads(2, 2);
  CHECK_THROWS_WITH_AS(frame_from_mesh(none, "f.msh"), doctest::Contains("no cell field \"Vinv\""), InputError);
  std::stringstream bad("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$FrameConvention\n$EndFrameConvention\n");
  CHECK_THROWS_WITH_AS(read_msh(bad, "e.msh"), doctest::Contains("empty $FrameConvention"), InputError);
}

TEST_CASE("an empty or default-built frame is an InputError where it is sampled, not an out-of-range read") {
  const Frame empty;
  CHECK_THROWS_WITH_AS(FrameSampler{empty}, doctest::Contains("the frame has 0 matrices M"), InputError);
  CHECK_THROWS_AS(empty.at_cells(make_structured_quads(2, 2)), InputError);
}

TEST_CASE("reflections: kept in M, removed by oriented(); the count is unchanged") {
  Mat2 F = Eigen::Vector2d(8, 32).asDiagonal();
  F.row(0) *= -1;  // det < 0
  Frame f = frame_from_mesh(untagged(2, F), "r.msh", SizeConvention::Quadapt);
  CHECK(f.M[0].determinant() < 0);
  const auto o = f.oriented();
  CHECK(o[0].determinant() > 0);
  CHECK((o[0].transpose() * o[0] - F.transpose() * F).norm() == 0);  // same metric M^T M
  CHECK(f.target_cells() == doctest::Approx(64));
}

TEST_CASE("rescale to a cell count and to a complexity") {
  Frame f = frame_from_mesh(untagged(3, frame_inverse(0.05, 3, 0.7)), "f", SizeConvention::Quadapt);
  const double target = cells_for_complexity(40000, 3);  // 2500 cells at p = 3
  CHECK(target == doctest::Approx(2500));
  const Frame g = f.scaled(f.scale_for_cells(target));
  CHECK(g.target_cells() == doctest::Approx(2500).epsilon(1e-12));
  CHECK_THROWS_AS(f.scaled(-1), InputError);
  CHECK_THROWS_AS(cells_for_complexity(1000, -1), InputError);
  // the cell metric measures a target edge as 1: V's columns are half-axes
  const auto [v, w] = frame_axes(f.M[0]);
  CHECK((f.cell_metric(0) * (2 * v)).norm() == doctest::Approx(1));
  CHECK((f.cell_metric(0) * (2 * w)).norm() == doctest::Approx(1));
}

TEST_CASE("sampler: M of the containing cell, the nearest outside") {
  Mesh m = make_structured_quads(2, 1);
  std::vector<Mat2> M = {Mat2::Identity(), 2 * Mat2::Identity()};
  set_frame_field(m, M);
  const Frame f = frame_from_mesh(m, "s");
  const FrameSampler s(f);
  bool inside = false;
  CHECK(s.cell(Vec2(0.25, 0.5), &inside) == 0);
  CHECK(inside);
  CHECK(s.at(Vec2(0.75, 0.5)) == M[1]);
  CHECK(s.cell(Vec2(1.5, 0.5), &inside) == 1);
  CHECK_FALSE(inside);
}

TEST_CASE("sampler: on a shared edge or vertex, the finest cell's M, whatever the cells' order") {
  // 2 x 2 cells with four different sizes; the shared edges and the middle vertex are sampled in
  // the background as built and with its cells in reverse order: the same M (before: the lowest
  // index, so the reversed background gave the other side's M)
  Mesh m = make_structured_quads(2, 2);
  std::vector<Mat2> M = {1.0 * Mat2::Identity(), 3.0 * Mat2::Identity(), 2.0 * Mat2::Identity(),
                         4.0 * Mat2::Identity()};
  Mesh r = m;
  std::reverse(r.cells.begin(), r.cells.end());
  std::vector<Mat2> Mr(M.rbegin(), M.rend());
  set_frame_field(m, M);
  set_frame_field(r, Mr);
  const Frame f = frame_from_mesh(m, "a"), g = frame_from_mesh(r, "b");
  const FrameSampler a(f), b(g);
  // cells: 0 (lower left, 1), 1 (lower right, 3), 2 (upper left, 2), 3 (upper right, 4)
  const std::vector<std::pair<Vec2, double>> points = {
      {Vec2(0.5, 0.25), 3}, {Vec2(0.25, 0.5), 2}, {Vec2(0.75, 0.5), 4}, {Vec2(0.5, 0.5), 4}, {Vec2(0.5, 0), 3}};
  for (const auto& [x, scale] : points) {
    CHECK(a.at(x) == scale * Mat2::Identity());
    CHECK(b.at(x) == scale * Mat2::Identity());
    int h = -1;
    CHECK(a.at(x, h) == scale * Mat2::Identity());
  }
}

TEST_CASE("FrameSampler::at with a hint: the same M as without, along a walk through the cells") {
  Mesh m = make_structured_quads(8, 8);
  for (Vec2& p : m.nodes) p = Vec2(p.x() + 0.2 * p.y() * p.y(), p.y());  // not axis-aligned
  std::vector<Mat2> M(m.num_cells());
  for (int c = 0; c < m.num_cells(); ++c) M[c] = (1.0 + c) * Mat2::Identity();
  set_frame_field(m, M);
  const Frame f = frame_from_mesh(m, "s");
  const FrameSampler s(f);
  int hint = -1, kept = 0;
  for (int k = 0; k <= 4000; ++k) {  // a slow walk: the hint is kept for many steps, then changes
    const Vec2 x(0.01 + 1.15 * k / 4000.0, 0.5 + 0.45 * std::sin(k / 300.0));
    const int before = hint;
    REQUIRE(s.at(x, hint) == s.at(x));
    kept += hint == before;
  }
  CHECK(kept > 3000);
  // on the edge between cells 3 and 4 (x = 0.5 + 0.025 y on the bottom row): either side's hint
  // gives locate's cell
  const Vec2 e(0.5 + 0.025e-3, 1e-3);
  for (int h : {-1, 3, 4}) {
    int hh = h;
    CHECK(s.at(e, hh) == s.at(e));
  }
}

TEST_CASE("write_frame: only Vinv and the tag, read back bit-exact") {
  Frame f = frame_from_mesh(untagged(2, frame_inverse(0.1, 2, 1.1)), "f", SizeConvention::Philip);
  const std::string path = (std::filesystem::temp_directory_path() / "quadapt_test_frame.msh").string();
  write_frame(f, path);
  const Frame g = read_frame(path);
  std::filesystem::remove(path);
  CHECK(g.source == SizeConvention::Quadapt);
  for (int c = 0; c < f.num_cells(); ++c) CHECK(g.M[c] == f.M[c]);
  CHECK(frame_mesh(f).cell_fields.size() == 1);
}
