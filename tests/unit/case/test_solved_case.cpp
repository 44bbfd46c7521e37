#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "case/case.hpp"
#include "case/solved_case.hpp"
#include "core/error.hpp"

using namespace quadapt;

namespace {
const char* kBase = R"J({"name": "a", "diffusion": [[0.5, 0], [0, 0.5]], "advection": [1, 2], "exact": "x*y + 1",
  "dirichlet": {"left": "0", "bottom": "x"}, "neumann": {"top": "y"}, "functional": {"boundary": "right"}})J";

std::vector<std::string> diff(const std::string& solved, const std::string& given) {
  return solved_case_differences(solved_case_record(parse_case(solved, "s.json"), 20), parse_case(given, "g.json"), "sol.msh");
}
}  // namespace

TEST_CASE("solved case: the same PDE however the file is written") {
  // name, description, functional, key order, blanks in expressions and numbers written as
  // expressions do not change the PDE
  CHECK(diff(kBase, R"J({"neumann": {"top": " y "}, "exact": "x * y+1", "advection": ["2/2", 2],
    "diffusion": [[0.5, 0], [0, "1/2"]], "dirichlet": {"bottom": "x", "left": "0"},
    "name": "b", "description": "other"})J")
            .empty());
  // a list of Dirichlet names in another order, with the functional added afterwards
  CHECK(diff(R"J({"advection": [1, 0], "exact": "x", "dirichlet": ["left", "bottom"]})J",
             R"J({"advection": [1, 0], "exact": "x", "dirichlet": ["bottom", "left"], "functional": {"boundary": "right"}})J")
            .empty());
}

TEST_CASE("solved case: each part of the PDE that differs is named") {
  CHECK(diff(kBase, R"J({"diffusion": [[0.5, 0], [0, 0.5]], "advection": [1, 2.5], "exact": "x*y + 1",
    "dirichlet": {"left": "0", "bottom": "x"}, "neumann": {"top": "y"}})J") == std::vector<std::string>{"advection"});
  CHECK(diff(kBase, R"J({"diffusion": [[0.4, 0], [0, 0.5]], "advection": [1, 2], "exact": "x*y + 2",
    "dirichlet": {"left": "0", "bottom": "x"}, "neumann": {"top": "y"}})J") ==
        std::vector<std::string>{"diffusion", "exact"});
  // the same Dirichlet boundaries, but data from u_exact (a list) instead of expressions (a map)
  CHECK(diff(kBase, R"J({"diffusion": [[0.5, 0], [0, 0.5]], "advection": [1, 2], "exact": "x*y + 1",
    "dirichlet": ["left", "bottom"], "neumann": {"top": "y"}})J") == std::vector<std::string>{"dirichlet_data"});
  // every boundary Dirichlet (the default) against a list
  CHECK(diff(R"J({"advection": [1, 0], "exact": "x"})J", R"J({"advection": [1, 0], "exact": "x", "dirichlet": ["left"]})J") ==
        std::vector<std::string>{"dirichlet"});
  CHECK(diff(kBase, R"J({"diffusion": [[0.5, 0], [0, 0.5]], "advection": [1, 2], "exact": "x*y + 1",
    "dirichlet": {"left": "0", "bottom": "x"}})J") == std::vector<std::string>{"neumann"});
}

TEST_CASE("solved case: a record that is not one is refused naming its file") {
  const Case cs = parse_case(kBase, "c.json");
  CHECK_THROWS_WITH_AS(solved_case_differences("{not json", cs, "sol.msh"), doctest::Contains("sol.msh"), InputError);
  CHECK_THROWS_WITH_AS(solved_case_differences("[1, 2]", cs, "sol.msh"), doctest::Contains("$SolvedCase"), InputError);
  // a record missing a key (written by another version) differs in that key
  CHECK(solved_case_differences(R"({"diffusion":[[0.5,0.0],[0.0,0.5]]})", cs, "sol.msh").size() == 5);
  CHECK_THROWS_WITH_AS(solved_penalty(R"({"penalty":"20"})", "sol.msh"), doctest::Contains("penalty"), InputError);
  CHECK_THROWS_WITH_AS(solved_penalty(R"({"penalty":0})", "sol.msh"), doctest::Contains("sol.msh"), InputError);
}

TEST_CASE("solved case: the penalty is recorded, not compared") {
  const Case cs = parse_case(kBase, "c.json");
  const std::string r = solved_case_record(cs, 37.5);
  CHECK(solved_penalty(r, "sol.msh") == 37.5);
  CHECK(solved_case_differences(r, cs, "sol.msh").empty());
  CHECK(solved_case_differences(solved_case_record(cs, 20), cs, "sol.msh").empty());
  CHECK(!solved_penalty(R"({"exact":"x"})", "sol.msh").has_value());
}
