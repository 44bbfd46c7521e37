#include <doctest/doctest.h>

#include "core/error.hpp"
#include "quad/mesh_utils.hpp"
#include "quad/recombine.hpp"
#include "test_meshes.hpp"

using namespace quadapt;

TEST_CASE("recombine: Delaunay of random points -> all quads, boundary and groups kept") {
  Mesh tri = testing::delaunay_unit_square(12, 400, 11);
  RecombineStats st;
  Mesh q = recombine_to_all_quads(tri, {}, &st);
  MESSAGE("triangles " << st.triangles_in << " parity " << st.parity_split << " -> quads " << st.blossom.quads
                       << " tris " << st.blossom.triangles << " -> " << st.cells_out << " quads, min angle "
                       << st.quality.min_angle_deg << " min SJ " << st.quality.min_scaled_jacobian);
  CHECK(q.all_quads());
  CHECK(st.blossom.triangles_in % 2 == 0);
  // Gmsh's topology clean-up removes a few nodes (two-quad nodes, diamonds), so the quads
  // number a little less than half the triangles; greedy matching would leave many triangles.
  CHECK(st.blossom.quads * 2 + st.blossom.triangles <= st.blossom.triangles_in);
  CHECK(st.blossom.quads * 2 + st.blossom.triangles >= 0.85 * st.blossom.triangles_in);
  CHECK(st.blossom.triangles <= st.blossom.triangles_in / 50);
  CHECK(q.num_cells() == 4 * st.blossom.quads + 3 * st.blossom.triangles);
  CHECK(total_area(q) == doctest::Approx(1.0).epsilon(1e-12));
  CHECK(st.quality.min_scaled_jacobian > 0);
  CHECK(q.groups.size() == 4);
  for (int g = 0; g < 4; ++g) {
    double len = 0;
    for (const auto& e : q.boundary)
      if (e.group == g) len += (q.nodes[e.v[1]] - q.nodes[e.v[0]]).norm();
    CHECK(len == doctest::Approx(1.0).epsilon(1e-12));
  }
  CHECK(free_edges(q).size() == q.boundary.size());
}

TEST_CASE("recombine: pairing mode keeps every node and pairs the input triangles exactly") {
  Mesh tri = testing::delaunay_unit_square(12, 400, 11);
  RecombineOptions opt;
  opt.blossom.gmsh_cleanup = false;
  opt.split = false;
  RecombineStats st;
  Mesh q = recombine_to_all_quads(tri, opt, &st);
  CHECK(2 * st.blossom.quads + st.blossom.triangles == st.blossom.triangles_in);
  // Gmsh 4.8's matching alone leaves ~5% of the triangles unmatched here (its clean-up then
  // removes them); the pairing keeps them as triangles.
  CHECK(st.blossom.triangles <= st.blossom.triangles_in / 10);
  CHECK(q.nodes == tri.nodes);
  for (int c = 0; c < q.num_cells(); ++c) CHECK(cell_scaled_jacobian(q, c) >= 0.01);
  CHECK(total_area(q) == doctest::Approx(1.0).epsilon(1e-12));
  CHECK(free_edges(q).size() == tri.boundary.size());
}

TEST_CASE("recombine: odd triangle count is made even and recombined") {
  Mesh tri = testing::delaunay_unit_square(10, 200, 4, 1, 1, true);
  REQUIRE(tri.num_cells() % 2 == 1);
  RecombineStats st;
  Mesh q = recombine_to_all_quads(tri, {}, &st);
  CHECK(st.parity_split);
  CHECK(st.blossom.triangles_in == tri.num_cells() + 1);
  CHECK(st.blossom.triangles <= 2);
  CHECK(q.all_quads());
  CHECK(st.quality.min_scaled_jacobian > 0);
  CHECK(total_area(q) == doctest::Approx(1.0).epsilon(1e-12));
}

TEST_CASE("recombine: structured right triangles pair into the squares") {
  Mesh tri = testing::structured_triangles(6, 5);
  RecombineStats st;
  Mesh q = recombine_to_all_quads(tri, {}, &st);
  CHECK(st.blossom.quads == 30);
  CHECK(st.blossom.triangles == 0);
  CHECK(st.quality.min_angle_deg == doctest::Approx(90).epsilon(1e-6));
}

TEST_CASE("recombine: bad input") {
  Mesh quads = make_structured_quads(2, 2);
  CHECK_THROWS_AS(recombine_to_all_quads(quads), InputError);
  Mesh tri = testing::structured_triangles(2, 2);
  std::swap(tri.cells[0].v[0], tri.cells[0].v[1]);  // clockwise triangle
  CHECK_THROWS_AS(recombine_to_all_quads(tri), InputError);
  Mesh empty;
  CHECK_THROWS_AS(recombine_to_all_quads(empty), InputError);
}

TEST_CASE("recombine: the metric matching without a frame is an InputError") {
  // it paired in x-y and returned quads, the header saying it "needs frame" (a library user's
  // review, session 38)
  RecombineOptions opt;
  opt.matching = RecombineOptions::Matching::Metric;
  CHECK_THROWS_WITH_AS(recombine_to_all_quads(testing::delaunay_unit_square(4, 20, 3), opt, nullptr, "t.msh"),
                       doctest::Contains("t.msh: the metric matching needs a frame"), InputError);
}
