// Files Gmsh writes in other forms than a plain save of an x-y mesh: partitioned (gmsh -part N),
// MSH 1, a mesh drawn in another plane.
#include <doctest/doctest.h>

#include <sstream>
#include <string>

#include "core/error.hpp"
#include "io/msh.hpp"

using namespace quadapt;

namespace {

// The unit square, six quads, `gmsh -2 -part 2 -format msh41` of a .geo with Physical Curves
// bottom, right, top, left (1..4) and Physical Surface domain (5), Gmsh 4.8.4: the elements sit on
// partitioned entities 5..11; curve 11 is the interface between the two partitions (its parent is
// the surface; it carries the surface's physical tag 5), and its four lines are interior edges.
const std::string kPartitioned = R"($MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
5
1 1 "bottom"
1 2 "right"
1 3 "top"
1 4 "left"
2 5 "domain"
$EndPhysicalNames
$Entities
4 4 1 0
1 0 0 0 0
2 1 0 0 0
3 1 1 0 0
4 0 1 0 0
1 0 0 0 1 0 0 1 1 2 1 -2
2 1 0 0 1 1 0 1 2 2 2 -3
3 0 1 0 1 1 0 1 3 2 3 -4
4 0 0 0 0 1 0 1 4 2 4 -1
1 0 0 0 1 1 0 1 5 4 1 2 3 4
$EndEntities
$PartitionedEntities
2
0
6 7 2 0
5 0 1 1 1 0 0 0 0
6 0 2 1 2 1 0 0 0
7 0 3 1 2 1 1 0 0
8 0 4 1 1 0 1 0 0
9 1 3 2 1 2 0.5000000000020591 1 0 1 3
10 1 1 2 1 2 0.499999999998694 0 0 1 1
5 1 1 1 1 0 0 0 0.499999999998694 0 0 1 1 2 5 -10
6 1 1 1 2 0.499999999998694 0 0 1 0 0 1 1 2 10 -6
7 1 2 1 2 1 0 0 1 1 0 1 2 2 6 -7
8 1 3 1 2 0.5000000000020591 1 0 1 1 0 1 3 2 7 -9
9 1 3 1 1 0 1 0 0.5000000000020591 1 0 1 3 2 9 -8
10 1 4 1 1 0 0 0 0 1 0 1 4 2 8 -5
11 2 1 2 1 2 0.3538373570722553 0 0 0.6494286120981281 1 0 1 5 2 10 -9
2 2 1 1 1 0 0 0 0.6494286120981281 1 0 1 5 4 5 9 10 11
3 2 1 1 2 0.3538373570722553 0 0 1 1 0 1 5 4 6 7 8 -11
$EndPartitionedEntities
$Nodes
15 11 1 11
0 5 0 1
1
0 0 0
0 6 0 1
2
1 0 0
0 7 0 1
3
1 1 0
0 8 0 1
4
0 1 0
0 9 0 1
7
0.5000000000020591 1 0
0 10 0 1
5
0.499999999998694 0 0
1 5 0 0
1 6 0 0
1 7 0 1
6
1 0.499999999998694 0
1 8 0 0
1 9 0 0
1 10 0 1
8
0 0.5000000000020591 0
1 11 0 3
9
11
10
0.5008681601796232 0.5000407391735244 0
0.6494286120981281 0.645533117253463 0
0.3538373570722553 0.3535353995019712 0
2 2 0 0
2 3 0 0
$EndNodes
$Elements
11 20 1 75
0 9 15 1
74 7
0 10 15 1
75 5
1 5 1 1
1 1 5
1 6 1 1
2 5 2
1 7 1 2
3 2 6
4 6 3
1 8 1 1
5 3 7
1 9 1 1
6 7 4
1 10 1 2
7 4 8
8 8 1
1 11 1 4
70 9 11
71 5 10
72 10 9
73 11 7
2 2 3 3
9 8 1 5 10
12 4 8 10 9
14 4 9 11 7
2 3 3 3
10 6 3 7 11
11 2 6 11 9
13 2 9 10 5
$EndElements
)";

// A quadrilateral, 14 quads, no physical groups, two partitions without partition topology
// (Gmsh 4.8.4; the test below says how it was made).
const std::string kUnnamedNoTopology = R"($MeshFormat
4.1 0 8
$EndMeshFormat
$Entities
4 4 1 0
1 0 0 0 0
2 2 0 0 0
3 1.5 1 0 0
4 0.2 1.2 0 0
1 0 0 0 2 0 0 0 2 1 -2
2 1.5 0 0 2 1 0 0 2 2 -3
3 0.2 1 0 1.5 1.2 0 0 2 3 -4
4 0 0 0 0.2 1.2 0 0 2 4 -1
1 0 0 0 2 1.2 0 0 4 1 2 3 4
$EndEntities
$PartitionedEntities
2
0
4 6 2 0
5 0 1 1 1 0 0 0 0
6 0 2 1 2 2 0 0 0
7 0 3 1 2 1.5 1 0 0
8 0 4 1 1 0.2 1.2 0 0
5 1 1 1 1 0 0 0 0.4999999999988218 0 0 0 0
6 1 1 1 2 0.4999999999988218 0 0 2 0 0 0 0
7 1 2 1 2 1.5 0 0 2 1 0 0 0
8 1 3 1 2 0.8500000000019172 1 0 1.5 1.099999999999705 0 0 0
9 1 3 1 1 0.2 1.099999999999705 0 0.8500000000019172 1.2 0 0 0
10 1 4 1 1 0 0 0 0.2 1.2 0 0 0
2 2 1 1 2 0.4999999999988218 0 0 2 1.099999999999705 0 0 0
3 2 1 1 1 0 0 0 0.8500000000019172 1.2 0 0 0
$EndPartitionedEntities
$Nodes
12 22 1 22
0 5 0 1
1
0 0 0
0 6 0 1
2
2 0 0
0 7 0 1
3
1.5 1 0
0 8 0 1
4
0.2 1.2 0
1 5 0 1
5
0.4999999999988218 0 0
1 6 0 2
6
7
0.9999999999973836 0 0
1.49999999999868 0 0
1 7 0 1
8
1.750000000000522 0.4999999999989554 0
1 8 0 2
9
10
1.175000000000985 1.049999999999848 0
0.8500000000019172 1.099999999999705 0
1 9 0 1
11
0.5250000000008928 1.149999999999863 0
1 10 0 3
12
13
14
0.1500000000001232 0.9000000000007391 0
0.100000000000257 0.600000000001542 0
0.05000000000012672 0.3000000000007603 0
2 2 0 5
22
19
16
18
15
1.047921475432578 0.3340945503345313 0
0.6687573786198782 0.4461173958709694 0
1.367084970416869 0.4630074494231136 0
0.9674429472591657 0.7593419592410967 0
0.7459346966716123 0.7914784709255303 0
2 3 0 3
20
17
21
0.3704793535565715 0.5415924249652969 0
0.2908220990113949 0.3140076566958727 0
0.4486668088020229 0.8463895622406823 0
$EndNodes
$Elements
12 32 1 32
0 5 15 1
1 1
0 6 15 1
2 2
0 7 15 1
3 3
0 8 15 1
4 4
1 5 1 1
5 1 5
1 6 1 3
6 5 6
7 6 7
8 7 2
1 7 1 2
9 2 8
10 8 3
1 8 1 2
11 3 9
12 9 10
1 9 1 2
13 10 11
14 11 4
1 10 1 4
15 4 12
16 12 13
17 13 14
18 14 1
2 2 3 7
19 5 6 22 19
20 9 16 8 3
22 16 7 2 8
23 16 22 6 7
24 9 18 22 16
25 9 10 15 18
27 22 18 15 19
2 3 3 7
21 5 19 20 17
26 11 4 12 21
28 14 17 20 13
29 10 11 21 15
30 13 20 21 12
31 19 15 21 20
32 17 14 1 5
$EndElements
)";

Mesh from_text(const std::string& text) {
  std::istringstream s(text);
  return read_msh(s, "part.msh");
}

int edges_of(const Mesh& m, const std::string& name) {
  const int g = m.find_group(name);
  int n = 0;
  for (const BoundaryEdge& e : m.boundary) n += e.group == g;
  return g < 0 ? -1 : n;
}

}  // namespace

TEST_CASE("a partitioned MSH 4.1 file reads as the unpartitioned mesh: its pieces are their parents") {
  // before: the lines sat on entities $Entities does not list, so they lost their names
  // (boundary_5 ... boundary_11), and the interface's lines were refused as interior edges
  const Mesh m = from_text(kPartitioned);
  CHECK(m.num_cells() == 6);
  REQUIRE(m.groups.size() == 4);
  for (const char* side : {"bottom", "right", "top", "left"}) CHECK(edges_of(m, side) == 2);
  CHECK(m.boundary.size() == 8);  // the interface's 4 lines are dropped
  CHECK(m.groups[m.find_group("right")].tag == 2);
  CHECK(m.domain_tag == 5);  // the surface piece's parent: 'domain'
}

TEST_CASE("partitioned, without partition topology and without physical groups: one group per model curve") {
  // a quadrilateral (0,0) (2,0) (1.5,1) (0.2,1.2), 14 quads, no physical groups,
  // `gmsh -2 -part 2 -setnumber Mesh.PartitionCreateTopology 0 -format msh41`: curves 1 and 3 are
  // each cut into two pieces (5, 6 and 8, 9); the unpartitioned file reads as boundary_1..4 with
  // 4, 2, 4, 4 edges. Before: seven groups boundary_5..boundary_11, and a case naming a curve's
  // group reached half of it or none.
  const Mesh m = from_text(kUnnamedNoTopology);
  CHECK(m.num_cells() == 14);
  REQUIRE(m.groups.size() == 4);
  CHECK(edges_of(m, "boundary_1") == 4);
  CHECK(edges_of(m, "boundary_2") == 2);
  CHECK(edges_of(m, "boundary_3") == 4);
  CHECK(edges_of(m, "boundary_4") == 4);
}

TEST_CASE("a partitioned entity whose parent has a lower dimension is refused") {
  std::string bad = kPartitioned;
  const std::string line = "5 1 1 1 1 0 0 0 0.499999999998694 0 0 1 1 2 5 -10";
  REQUIRE(bad.find(line) != std::string::npos);
  bad.replace(bad.find(line), line.size(), "5 0 1 1 1 0 0 0 0.499999999998694 0 0 1 1 2 5 -10");
  try {
    from_text(bad);
    FAIL("no error");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("part.msh") != std::string::npos);
    CHECK(std::string(e.what()).find("partitioned entity 5 of dimension 1 has a parent of dimension 0") != std::string::npos);
  }
}

TEST_CASE("an MSH 1 file is named as such, with the option that saves it readably") {
  try {
    from_text("$NOD\n4\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n$ENDNOD\n$ELM\n0\n$ENDELM\n");
    FAIL("no error");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()) == "part.msh: an MSH 1 file (it starts with $NOD): quadapt reads MSH 4.1 and 2.2; save "
                                   "it again from Gmsh with -format msh41 (or Mesh.MshFileVersion = 4.1)");
  }
}

TEST_CASE("a mesh drawn in the x-z plane is refused naming the plane (was: 'degenerate: zero area')") {
  const std::string xz = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 1 0 1\n4 0 0 1\n"
                         "$EndNodes\n$Elements\n1\n1 3 2 1 1 1 2 3 4\n$EndElements\n";
  try {
    from_text(xz);
    FAIL("no error");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()) == "part.msh: the mesh lies in the x-z plane (y = 0 at every node, z from 0 to 1): "
                                   "quadapt reads x and y only; turn it into the x-y plane (Gmsh: Rotate, or draw it there)");
  }
  // the same square in the x-y plane at z = 2 reads (z is ignored)
  std::string xy = xz;
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"3 1 0 1", "3 1 1 2"}, {"4 0 0 1", "4 0 1 2"},
                                 {"1 0 0 0", "1 0 0 2"}, {"2 1 0 0", "2 1 0 2"}})
    xy.replace(xy.find(from), from.size(), to);
  CHECK(from_text(xy).num_cells() == 1);
}
