#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "case/boundary_conditions.hpp"
#include "case/case.hpp"
#include "mesh/boundary.hpp"

using namespace quadapt;

namespace {
// The unit square in 2 x 2 quads; the file's lines cover x = 0 only (group 'left', tag 4) unless
// `left_line` is false; complete_boundary adds the other sides, as read_msh does.
Mesh square(bool left_line = true) {
  Mesh m;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) m.nodes.emplace_back(0.5 * i, 0.5 * j);
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      Cell c;
      c.nv = 4;
      const int a = 3 * j + i;
      c.v[0] = a, c.v[1] = a + 1, c.v[2] = a + 4, c.v[3] = a + 3;
      m.cells.push_back(c);
    }
  if (left_line) {
    m.groups.push_back({4, "left"});
    m.boundary.push_back({{6, 3}, 0});
    m.boundary.push_back({{3, 0}, 0});
  }
  complete_boundary(m);
  return m;
}

const GroupCondition* find(const std::vector<GroupCondition>& gs, const std::string& name) {
  for (const GroupCondition& g : gs)
    if (g.name == name) return &g;
  return nullptr;
}
}  // namespace

TEST_CASE("group conditions: each group's condition, data source and origin") {
  const Mesh m = square();
  const Case cs = parse_case(R"J({"diffusion": [[1, 0], [0, 1]], "exact": "x", "dirichlet": {"left": "0"}, "neumann": {"top": "1"},
    "functional": {"boundary": "right"}})J", "c.json");
  const auto gs = group_conditions(cs, m);
  REQUIRE(gs.size() == 4);
  const GroupCondition* left = find(gs, "left");
  REQUIRE(left);
  CHECK(left->dirichlet);
  CHECK(left->case_data);
  CHECK_FALSE(left->from_free_edges);
  CHECK(left->edges == 2);
  CHECK(left->tag == 4);
  const GroupCondition* top = find(gs, "top");
  REQUIRE(top);
  CHECK_FALSE(top->dirichlet);
  CHECK(top->case_data);
  CHECK(top->from_free_edges);
  const GroupCondition* bottom = find(gs, "bottom");
  REQUIRE(bottom);
  CHECK_FALSE(bottom->dirichlet);
  CHECK_FALSE(bottom->case_data);  // the exact solution's flux
  CHECK(find(gs, "right")->functional);
  CHECK(conditions_text(gs) ==
        "left: Dirichlet (case data); bottom: natural (exact flux), added from free edges; right: natural (exact flux), "
        "J, added from free edges; top: natural (case flux), added from free edges");
}

TEST_CASE("free-edge warning: groups quadapt made that the case leaves natural, in a file with lines of its own") {
  const Mesh m = square();
  // the file tags x = 0 only and the case lists it: bottom, right and top fall through
  const Case listed = parse_case(R"J({"diffusion": [[1, 0], [0, 1]], "exact": "x", "dirichlet": ["left"]})J", "c.json");
  const std::string w = free_edge_warning(listed, m, group_conditions(listed, m), "m.msh");
  CHECK(w.find("m.msh: 6 boundary edges carry no line of the file (first: ") == 0);
  CHECK(w.find("the groups 'bottom', 'right', 'top' of them, which c.json does not name, so they get the natural "
               "condition with the exact solution's flux") != std::string::npos);
  // every group the case names, by any key: nothing to say
  const Case named = parse_case(R"J({"diffusion": [[1, 0], [0, 1]], "exact": "x", "dirichlet": ["left", "bottom"], "neumann": {"top": "0"},
    "functional": {"boundary": "right"}})J", "c.json");
  CHECK(free_edge_warning(named, m, group_conditions(named, m), "m.msh").empty());
  // "dirichlet" absent: every group Dirichlet with u_exact
  const Case all = parse_case(R"J({"diffusion": [[1, 0], [0, 1]], "exact": "x"})J", "c.json");
  CHECK(free_edge_warning(all, m, group_conditions(all, m), "m.msh").empty());
  // a file without boundary lines (PHiLiP's, a frame's cells): the free edges are its boundary
  const Mesh bare = square(false);
  CHECK(free_edge_warning(listed, bare, group_conditions(listed, bare), "m.msh").empty());
  // one group left: singular wording
  const Case two = parse_case(R"J({"diffusion": [[1, 0], [0, 1]], "exact": "x", "dirichlet": ["left", "bottom", "right"]})J", "c.json");
  const std::string w1 = free_edge_warning(two, m, group_conditions(two, m), "m.msh");
  CHECK(w1.find("m.msh: 2 boundary edges") == 0);
  CHECK(w1.find("the group 'top' of them") != std::string::npos);
}
