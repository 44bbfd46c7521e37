// validate_mesh: each problem gives one InputError "PATH: problem" naming what is wrong.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "core/error.hpp"
#include "io/msh.hpp"
#include "mesh/validate.hpp"

using namespace quadapt;

namespace {
std::string problem(const Mesh& m, const ValidateOptions& opt = {}) {
  try {
    validate_mesh(m, "m.msh", opt);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}
bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

Mesh hanging() {  // a coarse cell beside two fine cells (2:1), boundary from the builder's names
  Mesh m;
  m.nodes = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {1, 0.5}, {1.5, 0}, {1.5, 0.5}, {1.5, 1}};
  m.cells = {Cell{{0, 1, 2, 3}, 4}, Cell{{1, 5, 6, 4}, 4}, Cell{{4, 6, 7, 2}, 4}};
  return m;
}
}  // namespace

TEST_CASE("valid meshes pass") {
  CHECK(problem(make_structured_quads(4, 3)) == "");
  CHECK(problem(make_perturbed_quads(6, 6, 0.3, 2), {CellKind::Quads, false, {"left", "top"}, {}}) == "");
  CHECK(problem(hanging()) == "");
}

TEST_CASE("each problem is named") {
  ValidateOptions quads;
  quads.require = CellKind::Quads;
  SUBCASE("no cells") {
    CHECK(problem(Mesh{}) == "m.msh: the mesh has no cells (no triangles or quadrangles)");
    Mesh lines = make_structured_quads(1, 1);  // Gmsh's file with physical curves but no Physical Surface
    lines.cells.clear();
    CHECK(has(problem(lines), "only boundary lines: Gmsh saves only the elements of physical groups, so add a Physical Surface"));
  }
  SUBCASE("non-finite coordinate") {
    Mesh m = make_structured_quads(2, 2);
    m.nodes[4].x() = NAN;
    CHECK(has(problem(m), "m.msh: node 5 has a non-finite coordinate"));
  }
  SUBCASE("node index out of range") {
    Mesh m = make_structured_quads(2, 2);
    m.cells[3].v[2] = 99;
    CHECK(problem(m) == "m.msh: cell 4 refers to node 100, which does not exist (9 nodes)");
  }
  SUBCASE("a triangle where quads are required") {
    Mesh m = make_structured_quads(2, 2);
    m.cells[1].nv = 3;
    m.cells[1].v[3] = -1;
    m.cells.push_back(Cell{{1, 5, 4, -1}, 3});
    m.cells[1].v = {1, 2, 5, -1};
    CHECK(problem(m) == "");
    std::string p = problem(m, quads);
    CHECK(has(p, "m.msh: cell 2 (centroid"));
    // a quad-dominant mesh: recombine takes all-triangle meshes, so the hint is Gmsh's full-quad options
    CHECK(has(p, "is a triangle, but quadrilaterals are required (2 triangles, 3 quadrilaterals; a quad-dominant mesh: in "
                 "Gmsh add Mesh.RecombinationAlgorithm = 2 (full-quad) or Mesh.SubdivisionAlgorithm = 1"));
    // all triangles: recombine does take them
    Mesh t;
    t.nodes = {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)};
    t.cells.push_back(Cell{{0, 1, 2, -1}, 3});
    CHECK(has(problem(t, quads), "(1 triangles, 0 quadrilaterals; in Gmsh: Recombine Surface, or recombine TRI.msh -o QUAD.msh)"));
  }
  SUBCASE("an inverted quad") {
    Mesh m = make_perturbed_quads(3, 3, 0.1, 1);
    m.nodes[5] = Vec2(0.9, 0.9);  // interior node (1,1) of the 4x4 node grid pushed past its neighbours
    std::string p = problem(m);
    CHECK(has(p, "m.msh: cell"));
    // the cells around the node: darts (one reflex corner, counter-clockwise outline) and
    // folded ones; the first invalid one is named
    CHECK((has(p, "is non-convex: reflex angle at corner") || has(p, "is inverted: negative Jacobian at corner")));
  }
  SUBCASE("a dart: one reflex corner is named as such") {
    Mesh m = make_structured_quads(2, 2);
    m.nodes[4] = Vec2(0.2, 0.2);  // centre node into cell 1, past its diagonal: cell 1 is a dart
    const std::string p = problem(m);
    CHECK(has(p, "m.msh: cell 1 (centroid"));
    CHECK(has(p, "is non-convex: reflex angle at corner 3 (0.2, 0.2) (a quad must be convex)"));
  }
  SUBCASE("every cell clockwise: one message saying so") {
    Mesh m = make_structured_quads(2, 2);
    for (Cell& c : m.cells) std::swap(c.v[1], c.v[3]);
    CHECK(has(problem(m), "m.msh: every cell is ordered clockwise; quadapt needs counter-clockwise cells"));
  }
  SUBCASE("one surface clockwise beside counter-clockwise ones: the ReverseMesh hint") {
    // Gmsh's two-surface mesh with one Curve Loop reversed (was: "22 invalid cells in all", no hint)
    Mesh m = make_structured_quads(4, 2);
    int reversed = 0;
    for (int c = 0; c < m.num_cells(); ++c)
      if (cell_centroid(m, c).x() > 0.5) {
        std::swap(m.cells[c].v[1], m.cells[c].v[3]);
        ++reversed;
      }
    REQUIRE(reversed == 4);
    const std::string p = problem(m);
    CHECK(has(p, "is inverted (ordered clockwise: every corner's Jacobian is negative) (4 of 8 cells, all of them "
                 "ordered clockwise: a surface meshed clockwise beside counter-clockwise ones? In Gmsh: ReverseMesh "
                 "Surface{...}; for it"));
    // another kind of problem among them: the plain count
    m.nodes[1] = Vec2(0.3, 0.6);
    CHECK(has(problem(m), "invalid cells in all)"));
  }
  SUBCASE("a reversed quad") {
    Mesh m = make_structured_quads(2, 2);
    std::swap(m.cells[0].v[1], m.cells[0].v[3]);
    CHECK(has(problem(m), "m.msh: cell 1 (centroid (0.25, 0.25)) is inverted (ordered clockwise"));
  }
  SUBCASE("a degenerate quad") {
    Mesh m = make_structured_quads(2, 2);
    m.nodes[4] = Vec2(0.25, 0.25);  // centre node onto the diagonal of cell 1: corner Jacobian 0
    std::string p = problem(m);
    CHECK(has(p, "m.msh: cell 1"));
    CHECK(has(p, "degenerate"));
  }
  SUBCASE("boundary edge in the interior") {
    Mesh m = make_structured_quads(2, 2);
    m.boundary.push_back({{1, 4}, 0});
    CHECK(has(problem(m), "of 'bottom' is not on the boundary of the mesh (it is an interior edge: a line on a curve "
                          "inside the domain"));
    CHECK(has(problem(m), "put the walls alone in Physical Curves"));  // Gmsh's save-all file: what to fix
    m.boundary.back() = {{0, 8}, 0};
    CHECK(has(problem(m), "(it is not an edge of any cell)"));
  }
  SUBCASE("hanging nodes when a conforming mesh is needed") {
    ValidateOptions conforming;
    conforming.allow_hanging_nodes = false;
    CHECK(has(problem(hanging(), conforming), "non-conforming (hanging node near (1, 0.25))"));
  }
  SUBCASE("missing boundary group, missing field, wrong field length") {
    Mesh m = make_structured_quads(2, 2);
    ValidateOptions o;
    o.required_groups = {"inflow"};
    CHECK(problem(m, o) == "m.msh: boundary 'inflow' not found (boundaries: bottom, right, top, left)");
    o.required_groups = {};
    o.required_fields = {"Vinv"};
    CHECK(problem(m, o) == "m.msh: field 'Vinv' not found (the file has no fields)");
    m.set_field(CellField{"h", 1, {1, 2, 3, 4}});
    CHECK(problem(m, o) == "m.msh: field 'Vinv' not found (fields: h)");
    m.cell_fields[0].values.pop_back();
    CHECK(problem(m) == "m.msh: field 'h' has 3 values, expected 4 cells x 1 components");
  }
}

TEST_CASE("Mesh::field_list names cell fields, then node fields as such, for messages") {
  Mesh m = make_structured_quads(2, 2);
  CHECK(m.field_list() == "none");
  m.set_field(CellNodeField{"u", 1, 4, 1, std::vector<double>(16, 0.0)});
  CHECK(m.field_list() == "u (node field)");
  m.set_field(CellField{"p", 1, {1, 2, 3, 4}});
  CHECK(m.field_list() == "p, u (node field)");
}

TEST_CASE("PHiLiP's frame files validate as quad meshes with Vinv") {
  ValidateOptions o;
  o.require = CellKind::Quads;
  o.required_groups = {"bottom", "right", "top", "left"};
  o.required_fields = {"Vinv"};
  const std::string dir = std::string(QUADAPT_FIXTURES_DIR) + "/";
  for (const char* f : {"input_ss15_fb_p1_3.msh", "input_bl15_adj_p2_3.msh"}) {
    CAPTURE(f);
    CHECK(problem(read_msh(dir + f), o) == "");
  }
}

TEST_CASE("an interface worse than 2:1 is refused, not taken as outer boundary") {
  // Coarse cell [0,1]^2 beside four fine cells of height 1/4 along x = 1 (4:1).
  Mesh m;
  m.nodes = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int k = 1; k <= 3; ++k) m.nodes.push_back({1, 0.25 * k});   // 4, 5, 6
  for (int k = 0; k <= 4; ++k) m.nodes.push_back({1.25, 0.25 * k}); // 7..11
  m.cells = {Cell{{0, 1, 2, 3}, 4}, Cell{{1, 7, 8, 4}, 4}, Cell{{4, 8, 9, 5}, 4},
             Cell{{5, 9, 10, 6}, 4}, Cell{{6, 10, 11, 2}, 4}};
  const std::string p = problem(m);
  CHECK(has(p, "m.msh: "));
  CHECK(has(p, "without sharing an edge"));
}

TEST_CASE("two blocks on duplicated nodes: the message says so and names Gmsh's Coherence") {
  // [0,1]x[0,1] and [1,2]x[0,1], each 1 x 2 cells, the nodes on x = 1 written twice (Gmsh
  // without Coherence). Was: "cells 1 and 3 meet along (1, 0.25) without sharing an edge".
  Mesh m = make_structured_quads(1, 2);
  const Mesh right = make_structured_quads(1, 2, 1, 2, 0, 1);
  const int off = m.num_nodes();
  for (const Vec2& p : right.nodes) m.nodes.push_back(p);
  for (Cell c : right.cells) {
    for (int k = 0; k < c.nv; ++k) c.v[k] += off;
    m.cells.push_back(c);
  }
  const std::string p = problem(m);
  CHECK(has(p, "m.msh: cells "));
  CHECK(has(p, "on duplicated nodes (two blocks whose shared nodes were not merged): merge them, in Gmsh with "
               "Coherence Mesh;"));
  // the same blocks 1e-3 apart are not duplicated nodes (a slit, or a gap)
  for (int i = off; i < m.num_nodes(); ++i) m.nodes[i].x() += 1e-3;
  CHECK_FALSE(has(problem(m), "duplicated nodes"));
}

TEST_CASE("far from the origin: areas and validity do not lose |x|^2 eps") {
  // a review (session 35): the shoelace sum on absolute coordinates made a unit grid at x = 1e7
  // "degenerate: zero area" and a 1e-3 cell at x = 1e3 7.6e-6 too large (relative)
  for (const double offset : {1e4, 1e7, 1e8}) {
    Mesh m = make_structured_quads(4, 3);
    const double a0 = total_area(m);
    for (auto& x : m.nodes) x += Vec2(offset, -offset);
    CHECK(problem(m) == "");
    CHECK(std::abs(total_area(m) - a0) <= 1e-14 * a0);
    for (int c = 0; c < m.num_cells(); ++c) CHECK(cell_area(m, c) > 0);
  }
  Mesh s = make_structured_quads(2, 2);
  const double a0 = total_area(s);
  for (auto& x : s.nodes) x = Vec2(1e3, 1e3) + 1e-3 * x;
  // the coordinates themselves carry 1e3 eps = 1e-13, 2e-10 of a cell's width: that much, no more
  CHECK(std::abs(total_area(s) - 1e-6 * a0) <= 1e-9 * 1e-6 * a0);
}
