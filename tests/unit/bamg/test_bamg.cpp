#include <doctest/doctest.h>

#include <Eigen/LU>
#include <cmath>
#include <sstream>

#include "bamg/bamgquad.hpp"
#include "bamg/frame_metric.hpp"
#include "bamg/inria_mesh.hpp"
#include "core/error.hpp"
#include "quad/mesh_utils.hpp"
#include "quad/quality_summary.hpp"

using namespace quadapt;

namespace {
// Frame on an n x n background of the unit square: V = R(theta) diag(h1, h2) everywhere.
Mesh constant_frame(int n, double theta_deg, double h1, double h2) {
  Mesh f = make_structured_quads(n, n);
  const double t = theta_deg * M_PI / 180;
  Eigen::Matrix2d R;
  R << std::cos(t), -std::sin(t), std::sin(t), std::cos(t);
  Eigen::Matrix2d M = Eigen::Vector2d(1 / h1, 1 / h2).asDiagonal() * R.transpose();
  CellField v{"Vinv", 9, {}};
  for (int c = 0; c < f.num_cells(); ++c)
    for (double x : {M(0, 0), M(0, 1), 0.0, M(1, 0), M(1, 1), 0.0, 0.0, 0.0, 0.0}) v.values.push_back(x);
  f.set_field(v);
  f.frame_convention = "quadapt";
  return f;
}
Frame as_frame(const Mesh& m) { return frame_from_mesh(m, "f"); }
}  // namespace

TEST_CASE("inria .mesh: write and read back") {
  InriaMesh m;
  m.vertices = {{0, 0}, {1, 0}, {1, 1}, {0, 1.0 / 3}};
  m.vertex_ref = {1, 0, 0, 2};
  m.triangles = {{0, 1, 2, 0}, {0, 2, 3, 0}};
  m.edges = {{0, 1, 1}, {1, 2, 2}, {2, 3, 3}, {3, 0, 4}};
  m.corners = {0, 1, 2, 3};
  std::stringstream s;
  write_inria_mesh(m, s);
  InriaMesh r = read_inria_mesh(s, "mem");
  CHECK(r.vertices.size() == 4);
  CHECK(r.vertices[3].y() == 1.0 / 3);  // 17 digits: exact
  CHECK(r.triangles == m.triangles);
  CHECK(r.edges == m.edges);
  CHECK(r.corners == m.corners);
  std::stringstream bad("MeshVersionFormatted 1\nDimension 2\nVertices\n2\n0 0 0\n1 x 0\n");
  CHECK_THROWS_AS(read_inria_mesh(bad, "bad"), InputError);
  std::stringstream bad2("MeshVersionFormatted 1\nDimension 2\nVertices\n1\n0 0 0\nTriangles\n1\n1 2 3 0\nEnd\n");
  CHECK_THROWS_AS(read_inria_mesh(bad2, "bad2"), InputError);
}

TEST_CASE("frame metric: sizes, log-Euclidean vertex mean, complexity") {
  Mesh f = constant_frame(4, 30, 0.05, 0.005);
  std::vector<Eigen::Matrix2d> M(f.num_cells());
  for (int c = 0; c < f.num_cells(); ++c) M[c] << f.cell_field("Vinv")->values[9 * c], f.cell_field("Vinv")->values[9 * c + 1],
                                                  f.cell_field("Vinv")->values[9 * c + 3], f.cell_field("Vinv")->values[9 * c + 4];
  CHECK(as_frame(f).target_cells() == doctest::Approx(1.0 / (4 * 0.05 * 0.005)));
  const double L = default_bamg_edge_factor();
  auto cm = bamg_cell_metrics(M, L);
  // the long axis (30 deg) has metric length 1 at L * h1, the short axis at L * h2
  Eigen::Vector2d u(std::cos(M_PI / 6), std::sin(M_PI / 6)), w(-u.y(), u.x());
  Eigen::Vector2d e1 = L * 0.05 * u, e2 = L * 0.005 * w;
  CHECK(std::sqrt(e1.dot(cm[0] * e1)) == doctest::Approx(1));
  CHECK(std::sqrt(e2.dot(cm[0] * e2)) == doctest::Approx(1));
  // triangles equilateral in the metric have area 8 h1 h2: sqrt(3)/4 / sqrt(det)
  CHECK(std::sqrt(3.0) / 4 / std::sqrt(cm[0].determinant()) == doctest::Approx(8 * 0.05 * 0.005));
  // log-Euclidean mean of two metrics with sizes h and 4h: the geometric mean size 2h
  Mesh two = make_structured_quads(2, 1);
  std::vector<Eigen::Matrix2d> mm = {Eigen::Matrix2d::Identity(), Eigen::Matrix2d::Identity() / 16.0};
  auto vm = vertex_metrics(two, mm, true);
  // node 1 (x = 0.5, y = 0) is shared by both cells
  CHECK(vm[1](0, 0) == doctest::Approx(0.25));
  CHECK(vm[0](0, 0) == doctest::Approx(1));
  auto va = vertex_metrics(two, mm, false);
  CHECK(va[1](0, 0) == doctest::Approx(17.0 / 32));
}

TEST_CASE("bamgquad: constant metric 0.1 along 30 deg, 0.01 across -> 10:1 quads along 30 deg") {
  // final quad edges 2 h1 = 0.1 along 30 degrees, 2 h2 = 0.01 across
  Mesh f = constant_frame(10, 30, 0.05, 0.005);
  BamgQuadStats st;
  Mesh q = bamg_quad(as_frame(f), {}, &st);
  const auto s = stretch_summary(q);
  MESSAGE("target " << st.target_complexity << " cells " << st.cells << " (ratio " << st.complexity_ratio << "), BAMG "
                    << st.bamg_triangles << " triangles -> " << st.recombine.blossom.quads << " quads + "
                    << st.recombine.blossom.triangles << " triangles; stretch mean " << s.mean_stretch << " at "
                    << s.mean_angle_deg << " deg, median " << s.median_stretch << " at " << s.median_angle_deg
                    << "; min SJ " << st.recombine.quality.min_scaled_jacobian << " min angle "
                    << st.recombine.quality.min_angle_deg);
  CHECK(q.all_quads());
  CHECK(st.recombine.quality.min_scaled_jacobian > 0);
  CHECK(std::abs(st.complexity_ratio - 1) < 0.15);
  CHECK(std::abs(s.median_stretch / 10 - 1) < 0.15);
  CHECK(std::abs(s.median_angle_deg - 30) < 5);
  CHECK(std::abs(s.mean_angle_deg - 30) < 5);
  CHECK(total_area(q) == doctest::Approx(1).epsilon(1e-12));
  // boundary names survive, each side's length is 1, and every free edge is named
  CHECK(q.groups.size() == 4);
  CHECK(q.find_group("bottom") >= 0);
  CHECK(q.find_group("left") >= 0);
  for (int g = 0; g < 4; ++g) {
    double len = 0;
    for (const auto& e : q.boundary)
      if (e.group == g) len += (q.nodes[e.v[1]] - q.nodes[e.v[0]]).norm();
    CHECK(len == doctest::Approx(1.0).epsilon(1e-12));
  }
  CHECK(free_edges(q).size() == q.boundary.size());
}

TEST_CASE("bamgquad: bad frames are rejected before anything runs") {
  Mesh f = constant_frame(3, 0, 0.1, 0.1);
  Mesh z = f;
  for (int k = 0; k < 9; ++k) z.cell_field("Vinv")->values[9 * 4 + k] = 0;  // det M = 0
  CHECK_THROWS_AS(bamg_quad(as_frame(z)), InputError);
  Mesh n = f;
  n.cell_field("Vinv")->values[9 * 2] = NAN;
  CHECK_THROWS_AS(bamg_quad(as_frame(n)), InputError);
  Mesh none = f;
  none.clear_fields();
  CHECK_THROWS_AS(bamg_quad(as_frame(none)), InputError);
}

TEST_CASE("ffbamg: a missing executable is an ExternalError") {
  Mesh f = constant_frame(3, 0, 0.1, 0.1);
  BamgQuadOptions opt;
  opt.ffbamg.executable = "/nonexistent/ffbamg";
  CHECK_THROWS_AS(bamg_quad(as_frame(f), opt), ExternalError);
}
