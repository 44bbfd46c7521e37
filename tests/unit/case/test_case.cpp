#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "case/case.hpp"
#include "core/error.hpp"

using namespace quadapt;

namespace {
std::string case_error(const std::string& text) {
  try {
    parse_case(text, "c.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}
bool has(const std::string& s, const std::string& sub) { return s.find(sub) != std::string::npos; }
}  // namespace

TEST_CASE("case: keys, defaults and constant expressions") {
  Case cs = parse_case(R"J({"diffusion": [["0.01*pi/e*12", "0.01*pi/e*3"], ["0.01*pi/e*3", "0.01*pi/e*20"]],
                           "advection": [1.1, "-pi/e"], "exact": "x*y",
                           "functional": {"boundary": "right"}})J",
                       "c.json");
  CHECK(cs.diffusion(0, 0) == doctest::Approx(0.12 * M_PI / M_E).epsilon(1e-15));
  CHECK(cs.diffusion(1, 1) == doctest::Approx(0.2 * M_PI / M_E).epsilon(1e-15));
  CHECK(cs.advection(1) == doctest::Approx(-M_PI / M_E).epsilon(1e-15));
  CHECK(cs.dirichlet_all);
  CHECK(cs.is_dirichlet("anything"));
  CHECK(cs.functional_boundary == "right");
  CHECK(!cs.advection_only());

  Case a = parse_case(R"J({"advection": [1, 1], "exact": "x", "dirichlet": ["left", "bottom"]})J", "a.json");
  CHECK(a.advection_only());
  CHECK(!a.dirichlet_all);
  CHECK(a.is_dirichlet("left"));
  CHECK(!a.is_dirichlet("right"));
  CHECK(!a.has_functional());
}

TEST_CASE("case: bad input is an InputError naming the file and the key") {
  std::string m = case_error(R"J({"exact": "x", "advection": [1, 0], "difusion": [[1,0],[0,1]]})J");
  CHECK(has(m, "c.json"));
  CHECK(has(m, "unknown key 'difusion'"));
  m = case_error(R"J({"exact": "sin(x))", "advection": [1, 0]})J");
  CHECK(has(m, "c.json: key 'exact': column 7"));
  CHECK(has(case_error(R"J({"advection": [1, 0]})J"), "missing key 'exact'"));
  CHECK(has(case_error(R"J({"exact": "x"})J"), "no PDE"));
  CHECK(has(case_error(R"J({"exact": "x", "diffusion": [[1, 2], [0, 1]]})J"), "symmetric"));
  CHECK(has(case_error(R"J({"exact": "x", "diffusion": [[1, 2], [2, 1]]})J"), "positive semi-definite"));
  CHECK(has(case_error(R"J({"exact": "x", "diffusion": [[1, 0]]})J"), "2x2"));
  CHECK(has(case_error(R"J({"exact": "x", "advection": [1, "x"]})J"), "constant"));
  CHECK(has(case_error(R"J({"exact": "x", "advection": [1, 0], "functional": {"boundry": "right"}})J"),
            "functional.boundry"));
  CHECK(has(case_error(R"J({"exact": "x", "advection": [1, 0], "dirichlet": [1]})J"), "dirichlet"));
  CHECK(has(case_error("{not json"), "not valid JSON"));
  CHECK_THROWS_AS(load_case("/nonexistent/case.json"), InputError);
}

TEST_CASE("case: boundary names are checked against the mesh") {
  Mesh m = make_structured_quads(2, 2);
  Case cs = parse_case(R"J({"exact": "x", "advection": [1, 0], "dirichlet": ["left", "inlet"]})J", "c.json");
  try {
    check_case_boundaries(cs, m);
    FAIL("expected an InputError");
  } catch (const InputError& e) {
    std::string s = e.what();
    CHECK(has(s, "c.json"));
    CHECK(has(s, "'inlet'"));
    CHECK(has(s, "bottom, right, top, left"));
  }
  Case f = parse_case(R"J({"exact": "x", "advection": [1, 0], "functional": {"boundary": "outlet"}})J", "f.json");
  CHECK_THROWS_AS(check_case_boundaries(f, m), InputError);
  Case ok = parse_case(R"J({"exact": "x", "advection": [1, 0], "dirichlet": ["left"], "functional": {"boundary": "right"}})J", "ok.json");
  CHECK_NOTHROW(check_case_boundaries(ok, m));
}

TEST_CASE("exact solution: S = div(D grad u) - c . grad u, exact for a polynomial") {
  // u = x^2 y + 3 x y^2: u_xx = 2y, u_xy = 2x + 6y, u_yy = 6x, u_x = 2xy + 3y^2, u_y = x^2 + 6xy.
  Case cs = parse_case(R"J({"exact": "x^2*y + 3*x*y^2", "diffusion": [[2, 0.5], [0.5, 3]], "advection": [1.5, -2]})J",
                       "p.json");
  ExactSolution ex(cs);
  for (auto [x, y] : {std::pair{0.3, 0.4}, std::pair{-1.0, 2.0}}) {
    double uxx = 2 * y, uxy = 2 * x + 6 * y, uyy = 6 * x, ux = 2 * x * y + 3 * y * y, uy = x * x + 6 * x * y;
    double S = 2 * uxx + 2 * 0.5 * uxy + 3 * uyy - 1.5 * ux + 2 * uy;
    std::vector<double> scratch(ex.scratch_size());
    double out[ExactSolution::NUM_OUTPUTS];
    ex.eval(x, y, out, scratch.data());
    CHECK(out[ExactSolution::U] == doctest::Approx(x * x * y + 3 * x * y * y).epsilon(1e-15));
    CHECK(out[ExactSolution::UX] == doctest::Approx(ux).epsilon(1e-15));
    CHECK(out[ExactSolution::UY] == doctest::Approx(uy).epsilon(1e-15));
    CHECK(out[ExactSolution::S] == doctest::Approx(S).epsilon(1e-14));
    CHECK(ex.source(x, y) == doctest::Approx(S).epsilon(1e-14));
  }
}

TEST_CASE("case: boundary data given as expressions (map forms of dirichlet and neumann)") {
  Case cs = parse_case(R"J({"diffusion": [[1, 0], [0, 1]], "exact": "x*y",
                           "dirichlet": {"inner": "0", "outer": "sin(x) + y^2"},
                           "neumann": {"right": 2.5}})J",
                       "c.json");
  CHECK_FALSE(cs.dirichlet_all);
  CHECK(cs.is_dirichlet("inner"));
  CHECK(cs.is_dirichlet("outer"));
  CHECK_FALSE(cs.is_dirichlet("right"));
  REQUIRE(cs.dirichlet_value("outer") != nullptr);
  CHECK(evaluate(cs.dirichlet_value("outer")->expr, 0.3, 2.0) == doctest::Approx(std::sin(0.3) + 4.0).epsilon(1e-15));
  CHECK(evaluate(cs.dirichlet_value("inner")->expr, 0.3, 2.0) == 0.0);
  CHECK(cs.dirichlet_value("right") == nullptr);
  REQUIRE(cs.neumann_value("right") != nullptr);
  CHECK(evaluate(cs.neumann_value("right")->expr, 0, 0) == 2.5);
  CHECK(cs.neumann_value("outer") == nullptr);

  // The list form keeps meaning "the exact solution's trace": no data expressions.
  Case list = parse_case(R"J({"diffusion": [[1, 0], [0, 1]], "exact": "x*y", "dirichlet": ["left"]})J", "c.json");
  CHECK(list.dirichlet_value("left") == nullptr);
  CHECK(list.is_dirichlet("left"));

  // Errors name the file, the key and the boundary.
  CHECK(has(case_error(R"J({"diffusion": [[1, 0], [0, 1]], "exact": "x", "dirichlet": {"outer": "2*z"}})J"),
            "c.json: key 'dirichlet.outer': column 3"));
  CHECK(has(case_error(R"J({"diffusion": [[1, 0], [0, 1]], "exact": "x", "dirichlet": {"outer": [1]}})J"),
            "key 'dirichlet.outer': expected an expression string"));
  CHECK(has(case_error(R"J({"diffusion": [[1, 0], [0, 1]], "exact": "x", "neumann": ["right"]})J"),
            "key 'neumann' must be a map"));
  CHECK(has(case_error(R"J({"diffusion": [[1, 0], [0, 1]], "exact": "x", "neumann": {"right": "1"}})J"),
            "boundary 'right' has Neumann data but is a Dirichlet boundary (\"dirichlet\" absent means every boundary"));
  // "dirichlet": "all" is present: the hint says so, not that the key is absent
  CHECK(has(case_error(R"J({"diffusion": [[1, 0], [0, 1]], "exact": "x", "dirichlet": "all", "neumann": {"right": "1"}})J"),
            "Dirichlet boundary (\"dirichlet\": \"all\" makes every boundary Dirichlet"));
  CHECK(has(case_error(R"J({"diffusion": [[1, 0], [0, 1]], "exact": "x", "dirichlet": ["left"],
                           "neumann": {"left": "1"}})J"),
            "boundary 'left' has Neumann data but is a Dirichlet boundary"));

  // Every named boundary must exist in the mesh.
  Mesh m = make_structured_quads(2, 2);
  Case bad = parse_case(R"J({"diffusion": [[1, 0], [0, 1]], "exact": "x", "dirichlet": ["left"],
                           "neumann": {"rigth": "1"}})J",
                        "c.json");
  try {
    check_case_boundaries(bad, m);
    FAIL("no error");
  } catch (const InputError& e) {
    CHECK(has(e.what(), "c.json: Neumann boundary 'rigth' is not a boundary group of the mesh"));
  }
}
