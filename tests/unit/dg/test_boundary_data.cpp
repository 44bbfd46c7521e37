// Boundary data given in the case file as expressions (docs/cases.md): the DG solution responds
// to them exactly as linearity predicts.
#include <doctest/doctest.h>

#include <string>

#include "case/case.hpp"
#include "dg/discretization.hpp"
#include "dg/linear_solver.hpp"

using namespace quadapt;

namespace {

Eigen::VectorXd solve_direct(const DGDiscretization& dg) {
  SparseMatrixCSC A;
  Eigen::VectorXd b;
  dg.assemble(A, b);
  LinearSolverOptions o;
  o.kind = LinearSolverKind::UmfPack;
  o.block_size = dg.dofs_per_cell();
  return solve_linear(A, b, o);
}

Mesh parallelograms(int n) {
  Mesh m = make_structured_quads(n, n);
  for (Vec2& x : m.nodes) x = Vec2(1.0 * x.x() + 0.4 * x.y(), 0.2 * x.x() + 0.9 * x.y());
  return m;
}

}  // namespace

TEST_CASE("Dirichlet data from the case map: data u_exact + 1 shifts the DG solution by exactly 1") {
  // DG(g + 1) - DG(g) is the DG solution with f = 0 and data 1, which is the constant 1 (inside
  // the space), so the difference is 1 to rounding — whatever the exact solution is.
  const Mesh m = parallelograms(3);
  const std::string head = R"J({"diffusion": [[1, 0.2], [0.2, 0.7]], "advection": [0.5, -0.3], "exact": "sin(2*x)*y^2 - y", )J";
  Case ref = parse_case(head + R"J("dirichlet": ["bottom", "right", "top", "left"]})J", "ref.json");
  const std::string g = "sin(2*x)*y^2 - y + 1";
  Case shifted = parse_case(head + R"J("dirichlet": {"bottom": ")J" + g + R"J(", "right": ")J" + g + R"J(", "top": ")J" + g +
                                R"J(", "left": ")J" + g + R"J("}})J",
                            "shifted.json");
  for (int p : {1, 3}) {
    DGDiscretization a(m, ref, p), b(m, shifted, p);
    Eigen::VectorXd d = solve_direct(b) - solve_direct(a);
    CHECK((d.array() - 1.0).abs().maxCoeff() < 1e-10);
  }
}

TEST_CASE("Neumann data from the case map: flux + 0.5 on the right adds exactly w = 0.5 x") {
  // Dirichlet on the left only; the right boundary's flux data is u_x + 0.5 instead of u_x.
  // The difference solves -lap w = 0, w = 0 on the left, w_x = 0.5 on the right, zero flux on
  // top and bottom: w = 0.5 x, which is in the space.
  const Mesh m = make_structured_quads(3, 4);
  const std::string head = R"J({"diffusion": [[1, 0], [0, 1]], "exact": "x^2*y - y", "dirichlet": ["left"])J";
  Case ref = parse_case(head + "}", "ref.json");
  Case same = parse_case(head + R"J(, "neumann": {"right": "2*x*y"}})J", "same.json");
  Case more = parse_case(head + R"J(, "neumann": {"right": "2*x*y + 0.5"}})J", "more.json");
  for (int p : {1, 2}) {
    DGDiscretization a(m, ref, p), s(m, same, p), b(m, more, p);
    const Eigen::VectorXd Ua = solve_direct(a);
    CHECK((solve_direct(s) - Ua).cwiseAbs().maxCoeff() < 1e-11);
    Eigen::VectorXd d = solve_direct(b) - Ua;
    double worst = 0;
    for (int c = 0; c < m.num_cells(); ++c)
      for (double xi : {-1.0, 0.3, 1.0})
        for (double eta : {-1.0, 0.5}) {
          const Vec2 x = map_to_physical(m, c, xi, eta);
          worst = std::max(worst, std::abs(b.evaluate(d, c, xi, eta) - 0.5 * x.x()));
        }
    CHECK(worst < 1e-10);
  }
}
