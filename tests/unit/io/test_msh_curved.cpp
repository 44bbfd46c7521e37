// Curved quads in MSH files: Gmsh's 9-, 16-, 25-, 36- and 49-node quadrangles (types 10, 36, 37,
// 38, 47) and their 3- to 7-node boundary lines, read with Gmsh's node ordering and written back.
// Fixtures: tests/golden/io/annulus_q{2,3,4,5,6}.msh = gmsh 4.8.4 `gmsh -2 -order q -setnumber N 2
// examples/geometry/annulus.geo` (annulus 1 <= r <= 2, 16 cells, inner/outer circles).
#include <doctest/doctest.h>

#include <cmath>
#include <sstream>
#include <string>

#include "core/error.hpp"
#include "io/msh.hpp"
#include "mesh/curved.hpp"
#include "mesh/validate.hpp"

using namespace quadapt;

namespace {
std::string fixture(int q) { return std::string(QUADAPT_SOURCE_DIR) + "/tests/golden/io/annulus_q" + std::to_string(q) + ".msh"; }
}  // namespace

TEST_CASE("curved MSH: Gmsh's node ordering of quads of order 2 to 6 and their boundary lines") {
  for (int q : {2, 3, 4, 5, 6}) {
    CAPTURE(q);
    const Mesh m = read_msh(fixture(q));
    REQUIRE(m.geometric_order() == q);
    CHECK(m.num_cells() == 16);
    CHECK(m.num_nodes() == 24);  // vertices only: 3 rings of 8
    CHECK(m.boundary.size() == 16);
    REQUIRE(m.find_group("inner") >= 0);
    REQUIRE(m.find_group("outer") >= 0);
    ValidateOptions v;
    v.allow_curved = true;
    validate_mesh(m, fixture(q), v);
    // Every edge's control points, in edge order, are where Gmsh put them: on a circle at
    // equal angle steps between the end vertices (arcs), or equally spaced (radial lines). A
    // wrong permutation of edge nodes or a reversed edge breaks this.
    int arcs = 0, lines = 0;
    for (int c = 0; c < m.num_cells(); ++c)
      for (int e = 0; e < 4; ++e) {
        const std::vector<int> idx = edge_control_points(q, e);
        const Vec2 a = m.cell_points(c)[idx.front()], b = m.cell_points(c)[idx.back()];
        CHECK(a == m.nodes[m.cells[c].v[e]]);
        CHECK(b == m.nodes[m.cells[c].v[(e + 1) % 4]]);
        // Arcs: edges on the boundary circles r = 1, 2 (interior edges are straight in Gmsh's mesh).
        const bool arc = std::abs(a.norm() - b.norm()) < 1e-12 &&
                         (std::abs(a.norm() - 1) < 1e-12 || std::abs(a.norm() - 2) < 1e-12);
        double ta = std::atan2(a.y(), a.x()), tb = std::atan2(b.y(), b.x());
        if (tb - ta > M_PI) tb -= 2 * M_PI;
        if (ta - tb > M_PI) tb += 2 * M_PI;
        for (int k = 1; k < q; ++k) {
          const Vec2 x = m.cell_points(c)[idx[k]];
          const double s = double(k) / q;
          if (arc) {
            const double t = ta + s * (tb - ta), r = a.norm();
            CHECK(std::abs(x.norm() - r) < 1e-12);
            // Gmsh's nodes are at equal parameter steps to ~5e-10 (its arc parametrisation);
            // a misplaced node would be off by a fraction of the edge (> 0.1 here).
            CHECK((x - r * Vec2(std::cos(t), std::sin(t))).norm() < 1e-8);
          } else {
            CHECK((x - ((1 - s) * a + s * b)).norm() < 1e-10);
          }
        }
        ++(arc ? arcs : lines);
      }
    CHECK(arcs == 16);  // 8 cells on each circle
    CHECK(lines == 48);
    // The interior control points (q >= 2) make a valid map, and the integral of det J over
    // the cells is the area enclosed by the (polynomial) boundary; the annulus is 3 pi.
    CHECK(min_scaled_jacobian(m).min > 0.5);
    // Measured |A - 3 pi| on this N = 2 mesh: q = 2: 7.3e-3, q = 3: 1.1e-3, q = 4: 1.1e-5,
    // q = 5: 1.2e-6, q = 6: 1.2e-8.
    // (A wrong order of the interior nodes of q = 5, 6 would leave an O(h^2) error.)
    const double tol[] = {0, 0, 1e-2, 2e-3, 2e-5, 2e-6, 2e-8};
    CHECK(std::abs(total_area(m) - 3 * M_PI) < tol[q]);
  }
}

TEST_CASE("curved MSH: write then read back is exact, and the text is stable") {
  for (int q : {2, 3, 4, 5, 6}) {
    CAPTURE(q);
    const Mesh m = read_msh(fixture(q));
    std::ostringstream os;
    write_msh(m, os);
    const std::string text = os.str();
    CHECK(text.find("\n2 1 " + std::to_string(gmsh_quad_type(q)) + " 16\n") != std::string::npos);
    CHECK(text.find("1 1 " + std::to_string(gmsh_line_type(q)) + " ") != std::string::npos);
    std::istringstream is(text);
    const Mesh r = read_msh(is, "round.msh");
    REQUIRE(r.geometric_order() == q);
    CHECK(r.nodes == m.nodes);
    CHECK(r.curved.points == m.curved.points);
    REQUIRE(r.num_cells() == m.num_cells());
    for (int c = 0; c < m.num_cells(); ++c) CHECK(r.cells[c].v == m.cells[c].v);
    REQUIRE(r.boundary.size() == m.boundary.size());
    for (size_t i = 0; i < m.boundary.size(); ++i) {
      CHECK(r.boundary[i].v == m.boundary[i].v);
      CHECK(r.groups[r.boundary[i].group].name == m.groups[m.boundary[i].group].name);
    }
    // Shared high-order nodes are written once: N + (edges (q-1) + cells (q-1)^2) nodes.
    const int edges = 4 * 2 * 3 + 4 * 2 * 2;  // 24 arcs/chords + 16 radial edges = 40
    const int nodes = 24 + edges * (q - 1) + 16 * (q - 1) * (q - 1);
    CHECK(text.find("$Nodes\n1 " + std::to_string(nodes) + " 1 " + std::to_string(nodes) + "\n") != std::string::npos);
    std::ostringstream again;
    write_msh(r, again);
    CHECK(again.str() == text);
  }
}

TEST_CASE("curved MSH: mixed geometric orders are refused with the element named") {
  // A 9-node quad followed by a 4-node quad.
  const std::string text =
      "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 12 1 12\n2 1 0 12\n"
      "1\n2\n3\n4\n5\n6\n7\n8\n9\n10\n11\n12\n"
      "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.5 0 0\n1 0.5 0\n0.5 1 0\n0 0.5 0\n0.5 0.5 0\n2 0 0\n2 1 0\n1.5 0.5 0\n"
      "$EndNodes\n$Elements\n2 2 1 2\n2 1 10 1\n1 1 2 3 4 5 6 7 8 9\n2 1 3 1\n2 2 10 11 3\n$EndElements\n";
  std::istringstream is(text);
  try {
    read_msh(is, "mixed.msh");
    FAIL("no error");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("mixed.msh") != std::string::npos);
    CHECK(std::string(e.what()).find("element 2 is a type 3 but earlier cells have geometric order 2") != std::string::npos);
  }
}
