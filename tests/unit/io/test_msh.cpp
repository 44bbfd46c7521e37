// read_msh / write_msh: exact round trips, golden files, MSH 2.2, PHiLiP's files, bad input.
#include <doctest/doctest.h>

#include <array>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <set>
#include <sstream>
#include <unistd.h>

#include "core/error.hpp"
#include "case/case.hpp"
#include "io/msh.hpp"
#include "mesh/boundary.hpp"
#include "mesh_compare.hpp"

using namespace quadapt;
namespace fs = std::filesystem;

namespace {

const std::string kGolden = std::string(QUADAPT_SOURCE_DIR) + "/tests/golden/io/";
const std::string kPhilip = std::string(QUADAPT_FIXTURES_DIR) + "/";

/// A perturbed grid carrying every field kind, with awkward numbers (1/3, -0, subnormals, huge).
Mesh mesh_with_every_field(int n, unsigned seed) {
  Mesh m = make_perturbed_quads(n, n, 0.2, seed);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double special[] = {1.0 / 3.0, -0.0, 5e-324, 2.2250738585072014e-308, 1.7976931348623157e308, -1e-300, 0.1};
  auto value = [&](size_t i) { return i % 11 < 7 ? special[i % 11] : u(rng) * std::pow(10.0, static_cast<int>(i % 40) - 20); };
  CellField h{"h", 1, {}};
  CellField vinv{"Vinv", 9, {}};
  for (int c = 0; c < m.num_cells(); ++c) {
    h.values.push_back(value(c));
    double a = u(rng), b = u(rng), cc = u(rng), d = u(rng);
    for (double v : {a, b, 0.0, cc, d, 0.0, 0.0, 0.0, 0.0}) vinv.values.push_back(v);
  }
  m.set_field(h);
  m.set_field(vinv);
  for (int p : {1, 3}) {
    CellNodeField f;
    f.name = "u" + std::to_string(p);
    f.degree = p;
    f.per_cell = (p + 1) * (p + 1);
    for (int i = 0; i < m.num_cells() * f.per_cell; ++i) f.values.push_back(value(i + 3));
    m.set_field(f);
  }
  CellNodeField vert{"corner_vectors", 2, 4, -1, {}};
  for (int i = 0; i < m.num_cells() * 8; ++i) vert.values.push_back(u(rng));
  m.set_field(vert);
  return m;
}

std::string to_text(const Mesh& m) {
  std::ostringstream s;
  write_msh(m, s);
  return s.str();
}

Mesh from_text(const std::string& text, const std::string& name = "text.msh") {
  std::istringstream s(text);
  return read_msh(s, name);
}

std::string error_of(const std::string& text, const std::string& name = "bad.msh") {
  try {
    from_text(text, name);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

}  // namespace

TEST_CASE("round trip write -> read is bit-exact for every field kind") {
  Mesh m = mesh_with_every_field(5, 7);
  Mesh r = from_text(to_text(m));
  test::check_same_mesh(m, r);
  CHECK(r.cell_node_field("u3")->degree == 3);
  CHECK(r.cell_node_field("corner_vectors")->degree == -1);
  CHECK(std::signbit(r.cell_field("h")->values[1]));  // -0 survives
  // and the text is a fixed point: write(read(write(m))) == write(m)
  CHECK(to_text(r) == to_text(m));
}

TEST_CASE("round trip through a file, with triangles and quads mixed") {
  Mesh m = make_structured_quads(3, 2);
  // split cell 2 into two triangles at the end and keep the others as quads
  Cell q = m.cells[2];
  m.cells.erase(m.cells.begin() + 2);
  Cell t1, t2;
  t1.nv = t2.nv = 3;
  t1.v = {q.v[0], q.v[1], q.v[2], -1};
  t2.v = {q.v[0], q.v[2], q.v[3], -1};
  m.cells.insert(m.cells.begin() + 1, t1);
  m.cells.push_back(t2);
  CellField f{"dwr", 1, {}};
  for (int c = 0; c < m.num_cells(); ++c) f.values.push_back(std::exp(-c) / 7);
  m.set_field(f);
  const fs::path tmp = fs::temp_directory_path() / ("quadapt_io_mixed_" + std::to_string(::getpid()) + ".msh");
  write_msh(m, tmp.string());
  Mesh r = read_msh(tmp.string());
  fs::remove(tmp);
  test::check_same_mesh(m, r);
  CHECK(r.num_triangles() == 2);
}

TEST_CASE("golden file: the writer's output is stable and reads back") {
  // tests/golden/io/square2_fields.msh was written by write_msh and checked by hand (and in
  // Gmsh): 2x2 grid, groups bottom/right/top/left, fields h, Vinv and a p=1 DG field u.
  Mesh m = make_structured_quads(2, 2);
  CellField h{"h", 1, {0.5, 0.25, 0.125, 1.0 / 3.0}};
  CellField vinv{"Vinv", 9, {}};
  for (int c = 0; c < 4; ++c)
    for (double v : {2.0 + c, 0.5, 0.0, -0.5, 4.0, 0.0, 0.0, 0.0, 0.0}) vinv.values.push_back(v);
  CellNodeField u{"u", 1, 4, 1, {}};
  for (int c = 0; c < 4; ++c)
    for (int k = 0; k < 4; ++k) u.values.push_back(c + 0.1 * k);
  m.set_field(h);
  m.set_field(vinv);
  m.set_field(u);
  const std::string golden = slurp(kGolden + "square2_fields.msh");
  REQUIRE(!golden.empty());
  CHECK(to_text(m) == golden);
  Mesh r = read_msh(kGolden + "square2_fields.msh");
  test::check_same_mesh(m, r);
}

TEST_CASE("MSH 2.2 ASCII with physical names, arbitrary tags and a time series") {
  const std::string text = R"($MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
3
1 7 "inflow"
1 8 "wall"
2 9 "fluid"
$EndPhysicalNames
$Nodes
5
10 0 0 0
20 2 0 0
30 2 1 0
40 0 1 0
50 1 0.5 0
$EndNodes
$Elements
8
1 15 2 0 1 10
2 1 2 7 1 40 10
3 1 2 8 2 10 20
4 1 2 8 2 20 30
5 1 2 8 2 30 40
6 2 2 9 1 10 20 50
7 3 2 9 1 20 30 40 50
8 2 2 9 1 50 40 10
$EndElements
$ElementData
1
"rho"
1
0.0
3
0
1
3
6 1.5
7 2.5
8 3.5
$EndElementData
$ElementData
1
"rho"
1
1.0
3
1
1
3
6 10
7 20
8 30
$EndElementData
)";
  Mesh m = from_text(text);
  CHECK(m.num_nodes() == 5);
  CHECK(m.num_cells() == 3);
  CHECK(m.num_quads() == 1);
  CHECK(m.cells[1].v == std::array<int, 4>{1, 2, 3, 4});
  CHECK(m.domain_name == "fluid");
  CHECK(m.domain_tag == 9);
  REQUIRE(m.groups.size() == 2);
  CHECK(m.groups[0].name == "inflow");
  CHECK(m.groups[1].name == "wall");
  CHECK(m.boundary.size() == 4);
  CHECK(total_area(m) == doctest::Approx(2.0));
  const CellField* rho = m.cell_field("rho");
  REQUIRE(rho);
  CHECK(rho->values == std::vector<double>{10, 20, 30});  // the last time step
}

namespace {
/// MSH 4.1 $Nodes of the unit square's corners 1..4 (counter-clockwise from (0, 0)), one block
/// on surface entity 9.
const std::string kSquareNodes41 = R"($Nodes
1 4 1 4
2 9 0 4
1
2
3
4
0 0 0
1 0 0
1 1 0
0 1 0
$EndNodes
)";
}  // namespace

TEST_CASE("lines without physical names: unit-square sides, else boundary_<tag>") {
  // MSH 4.1 with $Entities: curve 5 has physical tag 2 (no name), curve 6 none.
  const std::string text = R"($MeshFormat
4.1 0 8
$EndMeshFormat
$Entities
0 2 1 0
5 0 0 0 1 0 0 1 2 0
6 0 0 0 1 1 0 0 0
9 0 0 0 1 1 0 0 2 5 6
$EndEntities
)" + kSquareNodes41 + R"($Elements
3 5 1 5
1 5 1 1
1 1 2
1 6 1 3
2 2 3
3 3 4
4 4 1
2 9 3 1
5 1 2 3 4
$EndElements
)";
  Mesh m = from_text(text);
  REQUIRE(m.groups.size() == 2);
  CHECK(m.groups[0].name == "bottom");
  CHECK(m.groups[0].tag == 2);
  CHECK(m.groups[1].name == "boundary_6");  // spans three sides: not one of them
  CHECK(m.groups[1].tag == 6);
  CHECK(m.boundary.size() == 4);
}

TEST_CASE("every PHiLiP fixture reads as it is, with named boundaries") {
  int files = 0;
  for (const auto& entry : fs::directory_iterator(kPhilip)) {
    if (entry.path().extension() != ".msh") continue;
    const std::string name = entry.path().filename().string();
    CAPTURE(name);
    Mesh m = read_msh(entry.path().string());
    ++files;
    CHECK(m.num_cells() > 100);
    CHECK(m.all_quads());
    CHECK(total_area(m) == doctest::Approx(1.0).epsilon(1e-9));
    std::vector<std::string> names;
    for (const auto& g : m.groups) names.push_back(g.name);
    std::sort(names.begin(), names.end());
    CHECK(names == std::vector<std::string>{"bottom", "left", "right", "top"});
    // every free edge is covered, every boundary edge lies on the side it is named after
    CHECK(boundary_free_edges(m).size() == m.boundary.size());
    for (const BoundaryEdge& e : m.boundary)
      CHECK(unit_square_side(m.nodes[e.v[0]], m.nodes[e.v[1]], 1e-6) == m.groups[e.group].name);
    if (name.rfind("input_", 0) == 0) {
      const CellField* v = m.cell_field("Vinv");
      REQUIRE(v);
      CHECK(v->ncomp == 9);
      for (int c = 0; c < m.num_cells(); ++c) {
        CHECK((*v)(c, 2) == 0.0);
        CHECK((*v)(c, 8) == 0.0);
      }
    }
    // and survives a round trip exactly
    Mesh r = from_text(to_text(m));
    test::check_same_mesh(m, r);
  }
  CHECK(files == 16);
}

TEST_CASE("PHiLiP frame: first and last Vinv rows as in the file") {
  Mesh m = read_msh(kPhilip + "input_bl15_adj_p2_3.msh");
  CHECK(m.num_nodes() == 995);
  CHECK(m.num_cells() == 957);
  const CellField& v = *m.cell_field("Vinv");
  CHECK(v(0, 0) == -4.89119);
  CHECK(v(0, 4) == 58.2777);
  CHECK(v(956, 0) == 4.99964e-15);
  CHECK(v(956, 3) == 1394.84);
  // No boundary lines in the file: the square's sides from the free edges, tags 1..4.
  CHECK(m.groups[0].name == "bottom");
  CHECK(m.groups[0].tag == 1);
  CHECK(m.groups[3].name == "left");
}

TEST_CASE("bad input: one InputError naming the file and the problem") {
  const std::string good = to_text(make_structured_quads(2, 2));
  auto msg = [](const std::string& text) { return error_of(text, "bad.msh"); };
  SUBCASE("empty") { CHECK(msg("").find("bad.msh: empty file") == 0); }
  SUBCASE("not msh") { CHECK(msg("hello\n").find("not a Gmsh MSH file") != std::string::npos); }
  SUBCASE("wrong version") {
    std::string t = good;
    t.replace(t.find("4.1 0 8"), 7, "5.0 0 8");
    CHECK(msg(t) == "bad.msh: $MeshFormat: unsupported MSH format version '5.0' (supported: 4.1 and 2.2)");
  }
  SUBCASE("truncated in $Nodes") {
    std::string t = good.substr(0, good.find("$EndNodes") - 10);
    CHECK(msg(t).find("bad.msh: $Nodes: truncated file") == 0);
  }
  SUBCASE("truncated anywhere: always an InputError") {
    for (size_t cut = 1; cut + 1 < good.size(); cut += 37) {
      std::string e = msg(good.substr(0, cut));
      CHECK_MESSAGE(e.rfind("bad.msh: ", 0) == 0, "cut at " << cut << ": " << e);
    }
  }
  SUBCASE("missing $Nodes") {
    size_t a = good.find("$Nodes"), b = good.find("$EndNodes") + 10;
    std::string t = good.substr(0, a) + good.substr(b);
    std::string e = msg(t);
    CHECK(e.find("bad.msh: ") == 0);
    CHECK((e.find("missing $Nodes") != std::string::npos || e.find("before $Nodes") != std::string::npos));
  }
  SUBCASE("missing $Elements") {
    size_t a = good.find("$Elements"), b = good.find("$EndElements") + 13;
    CHECK(msg(good.substr(0, a) + good.substr(b)) == "bad.msh: missing $Elements section");
  }
  SUBCASE("NaN coordinate") {
    std::string t = good;
    size_t at = t.find("0.5 0 0");
    REQUIRE(at != std::string::npos);
    t.replace(at, 3, "nan");
    CHECK(msg(t).find("bad.msh: $Nodes: node") == 0);
    CHECK(msg(t).find("non-finite coordinate") != std::string::npos);
  }
  SUBCASE("unknown node") {
    std::string t = good;
    size_t at = t.find("\n1 1 2 5 4\n");
    REQUIRE(at != std::string::npos);
    t.replace(at, 11, "\n1 1 2 5 99\n");
    CHECK(msg(t).find("refers to node 99") != std::string::npos);
  }
  SUBCASE("unsupported element type") {
    std::string t = good;
    size_t at = t.find("\n2 1 3 4\n");
    REQUIRE(at != std::string::npos);
    t.replace(at, 9, "\n2 1 16 4\n");
    CHECK(msg(t).find("8-node quadrangle is not supported") != std::string::npos);
    CHECK(msg(t).find("Mesh.SecondOrderIncomplete = 1: set it to 0") != std::string::npos);
    t = good;
    t.replace(at, 9, "\n2 1 5 4\n");  // an 8-node hexahedron
    CHECK(msg(t).find("quadapt is 2D: mesh the surface only (gmsh -2)") != std::string::npos);
  }
  SUBCASE("field without a value for a cell") {
    Mesh m = make_structured_quads(2, 2);
    m.set_field(CellField{"h", 1, {1, 2, 3, 4}});
    std::string t = to_text(m);
    size_t at = t.find("\n4 4\n");
    REQUIRE(at != std::string::npos);
    t.replace(at, 5, "\n");
    t.replace(t.find("\n4\n1 1\n"), 7, "\n3\n1 1\n");
    CHECK(msg(t) == "bad.msh: view 'h' has no value for element 4 (every cell needs one)");
  }
  SUBCASE("unreadable path") {
    try {
      read_msh("/nonexistent/dir/x.msh");
      FAIL("no error");
    } catch (const InputError& e) {
      CHECK(std::string(e.what()).find("/nonexistent/dir/x.msh: cannot open") == 0);
    }
  }
}

TEST_CASE("a line group keyed by its entity whose tag is taken, beside a physical tag INT_MAX: the smallest free tag") {
  // "largest used + 1" overflowed when a file gave 2147483647 (found by fuzzing under UBSan).
  const std::string text = R"($MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
2
1 1 "bottom"
1 2147483647 "right"
$EndPhysicalNames
$Nodes
4
1 0 0 0
2 1 0 0
3 1 1 0
4 0 1 0
$EndNodes
$Elements
5
1 1 2 1 1 1 2
2 1 2 2147483647 2 2 3
3 1 2 0 1 3 4
4 1 2 1 1 4 1
5 3 2 5 1 1 2 3 4
$EndElements
)";
  Mesh m = from_text(text);
  REQUIRE(m.groups.size() == 3);
  std::set<int> tags;
  for (const auto& g : m.groups) tags.insert(g.tag);
  CHECK(tags == std::set<int>{1, 2, 2147483647});
}

TEST_CASE("$SolvedCase: one line of JSON, blanks inside kept, travels with the fields and is cleared with them") {
  Mesh m = make_structured_quads(2, 2);
  CellNodeField u{"u", 1, 4, 1, {}};
  for (int c = 0; c < 4; ++c)
    for (int k = 0; k < 4; ++k) u.values.push_back(c + 0.1 * k);
  m.set_field(u);
  m.solved_case = R"({"exact":"a b","neumann":{}})";  // blanks inside a string must survive
  const std::string text = to_text(m);
  CHECK(text.find("$SolvedCase\n{\"exact\":\"a b\",\"neumann\":{}}\n$EndSolvedCase\n") != std::string::npos);
  Mesh r = from_text(text);
  CHECK(r.solved_case == m.solved_case);
  test::check_same_mesh(m, r);
  CHECK(to_text(r) == text);
  r.clear_fields();
  CHECK(r.solved_case.empty());
  CHECK(to_text(r).find("SolvedCase") == std::string::npos);
  CHECK(error_of("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$SolvedCase\n$EndSolvedCase\n").find("empty $SolvedCase") !=
        std::string::npos);
  CHECK(error_of("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$SolvedCase\n{}\n").find("bad.msh: $SolvedCase") != std::string::npos);
}

namespace {
/// MSH 2.2 text of the unit square as 2 x 2 quads (nodes 1..9, node i + 3j + 1 at (i/2, j/2))
/// with the boundary lines given as "phys entity a b" rows and the $PhysicalNames given.
int edges_of(const Mesh& m, const std::string& group) {
  const int g = m.find_group(group);
  int n = 0;
  for (const BoundaryEdge& be : m.boundary) n += be.group == g;
  return g < 0 ? -1 : n;
}
std::string square22(const std::vector<std::array<long long, 4>>& lines, const std::string& names = "") {
  std::ostringstream o;
  o << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";
  if (!names.empty()) o << "$PhysicalNames\n" << names << "$EndPhysicalNames\n";
  o << "$Nodes\n9\n";
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) o << i + 3 * j + 1 << ' ' << i * 0.5 << ' ' << j * 0.5 << " 0\n";
  o << "$EndNodes\n$Elements\n" << lines.size() + 4 << '\n';
  int t = 1;
  for (const auto& l : lines) o << t++ << " 1 2 " << l[0] << ' ' << l[1] << ' ' << l[2] << ' ' << l[3] << '\n';
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const int n = i + 3 * j + 1;
      o << t++ << " 3 2 1 1 " << n << ' ' << n + 1 << ' ' << n + 4 << ' ' << n + 3 << '\n';
    }
  o << "$EndElements\n";
  return o.str();
}
}  // namespace

TEST_CASE("a boundary edge in two physical groups is refused naming both (a condition was silently lost)") {
  // Gmsh's 2.2 writer repeats a line once per physical group: 'right' and 'outflow' on x = 1
  const std::string names = "2\n1 2 \"right\"\n1 7 \"outflow\"\n";
  const std::string e = error_of(square22({{2, 2, 3, 6}, {2, 2, 6, 9}, {7, 2, 3, 6}, {7, 2, 6, 9}}, names));
  CHECK(e.find("bad.msh: the boundary edge (1, 0) - (1, 0.5) is in physical group 2 ('right') and in physical group 7 "
               "('outflow')") != std::string::npos);
  CHECK(e.find("keep one Physical Curve per curve") != std::string::npos);
  // the same line twice in one group is one edge
  Mesh m = from_text(square22({{2, 2, 3, 6}, {2, 2, 6, 9}, {2, 2, 6, 3}}, names));
  CHECK(m.boundary.size() == 8);  // 2 read + 6 completed
  CHECK(edges_of(m, "right") == 2);
  // MSH 4.1: one curve entity with two physical tags
  const std::string text41 = R"($MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
2
1 2 "right"
1 7 "outflow"
$EndPhysicalNames
$Entities
0 1 1 0
5 1 0 0 1 1 0 2 2 7 0
9 0 0 0 1 1 0 0 0
$EndEntities
)" + kSquareNodes41 + R"($Elements
2 2 1 2
1 5 1 1
1 2 3
2 9 3 1
2 1 2 3 4
$EndElements
)";
  CHECK(error_of(text41).find("curve 5 is in physical groups 2 ('right') and 7 ('outflow')") != std::string::npos);
}

TEST_CASE("a boundary edge in two groups, one of them at the most negative tag: named right, no overflow") {
  // the group key was a signed tag (physical tag, or minus the entity tag), negated again for the
  // message: a physical tag of -2^63 was called a curve and its negation overflowed (the fuzzer,
  // under UBSan). A negative physical tag is a physical group all the same (refused later as out
  // of range when it stands alone).
  const long long most_negative = std::numeric_limits<long long>::min();
  const std::string e = error_of(square22({{most_negative, 2, 3, 6}, {2, 2, 3, 6}}));
  CHECK(e.find("bad.msh: the boundary edge (1, 0) - (1, 0.5) is in physical group -9223372036854775808 and in "
               "physical group 2") != std::string::npos);
  const std::string c = error_of(square22({{0, most_negative, 3, 6}, {0, 5, 3, 6}}));
  CHECK(c.find("is in curve -9223372036854775808 and in curve 5") != std::string::npos);
}

TEST_CASE("unnamed curves on one side of the unit square all take the side's name") {
  // no physical groups: each curve is its own entity; x = 0 is made of two curves (5 and 6)
  Mesh m = from_text(square22({{0, 1, 1, 2}, {0, 1, 2, 3}, {0, 2, 3, 6}, {0, 2, 6, 9}, {0, 3, 9, 8}, {0, 3, 8, 7},
                               {0, 5, 7, 4}, {0, 6, 4, 1}}));
  REQUIRE(m.groups.size() == 4);  // before: left + boundary_6, and a case's "left" covered half the side
  CHECK(edges_of(m, "left") == 2);
  for (const char* side : {"bottom", "right", "top"}) CHECK(edges_of(m, side) == 2);
}

TEST_CASE("a physical tag beyond an int is refused, not wrapped") {
  const std::string e = error_of(square22({{2147483653LL, 2, 3, 6}}, "1\n1 2147483653 \"right\"\n"));
  CHECK(e.find("bad.msh: physical tag 2147483653 is out of range") != std::string::npos);
  // an entity tag beyond an int (no physical group) gets a free tag
  Mesh m = from_text(square22({{0, 4294967301LL, 3, 6}, {0, 4294967301LL, 6, 9}}));
  CHECK(edges_of(m, "right") == 2);
  CHECK(m.groups[m.find_group("right")].tag > 0);
}

TEST_CASE("MSH 2.2 saved with Mesh.SaveAll: declared side names take the lines Gmsh wrote with physical tag 0") {
  // $PhysicalNames lists the four sides, but every line carries physical tag 0 and its curve as
  // entity; before, bottom..left stayed empty beside boundary_1..4 and a case's 'right' was refused
  const std::string names = "4\n1 1 \"bottom\"\n1 2 \"right\"\n1 3 \"top\"\n1 4 \"left\"\n";
  Mesh m = from_text(square22({{0, 1, 1, 2}, {0, 1, 2, 3}, {0, 2, 3, 6}, {0, 2, 6, 9}, {0, 3, 9, 8}, {0, 3, 8, 7},
                               {0, 4, 7, 4}, {0, 4, 4, 1}},
                              names));
  REQUIRE(m.groups.size() == 4);
  for (const char* side : {"bottom", "right", "top", "left"}) CHECK(edges_of(m, side) == 2);
  CHECK(m.groups[m.find_group("right")].tag == 2);  // the declared physical tag
}

TEST_CASE("a directory given as a mesh or a case is an InputError, not std::ios_base::failure") {
  // the read of a directory threw std::ios_base::failure past every `catch (const quadapt::Error&)`
  // (a library user's review, session 38)
  const std::string dir = std::filesystem::temp_directory_path().string();
  CHECK_THROWS_WITH_AS(read_msh(dir), doctest::Contains("is a directory, not a file"), InputError);
  CHECK_THROWS_WITH_AS(load_case(dir), doctest::Contains("is a directory, not a file"), InputError);
}
