// upwind_order (lib/dg/solve.hpp): a topological order of the upwind graph, which the centroid
// order (downwind_order) is not on sheared or stretched, staggered cells — there the pure-advection
// solves (block ILU in dgsolve, the adjoint's block sweep) are exact only in upwind_order.
#include <doctest/doctest.h>

#include <algorithm>
#include <numeric>

#include "adjoint/block_sweep.hpp"
#include "case/case.hpp"
#include "dg/block_matrix.hpp"
#include "dg/discretization.hpp"
#include "dg/solve.hpp"
#include "mesh/topology.hpp"

using namespace quadapt;

namespace {
/// Interior faces with c . n != 0 whose upwind cell comes after its downwind cell in `order`.
int faces_against(const Mesh& m, const std::vector<int>& order, const Eigen::Vector2d& c) {
  std::vector<int> pos(m.num_cells());
  for (int k = 0; k < static_cast<int>(order.size()); ++k) pos[order[k]] = k;
  int bad = 0;
  for (const Face& f : build_topology(m).faces) {
    const double s = c.dot(f.normal);
    if (f.is_boundary() || s == 0) continue;
    const int up = s > 0 ? f.cell[0] : f.cell[1], down = s > 0 ? f.cell[1] : f.cell[0];
    if (pos[up] > pos[down]) ++bad;
  }
  return bad;
}

bool is_permutation_of_cells(const Mesh& m, std::vector<int> order) {
  std::sort(order.begin(), order.end());
  std::vector<int> all(m.num_cells());
  std::iota(all.begin(), all.end(), 0);
  return order == all;
}

/// The unit square's 12 x 12 grid sheared by x += y: parallelograms leaning at 45 degrees.
Mesh sheared_grid() {
  Mesh m = make_structured_quads(12, 12);
  for (Vec2& x : m.nodes) x.x() += x.y();
  return m;
}
}  // namespace

TEST_CASE("upwind order: the centroid order itself where that is topological") {
  const Mesh m = make_structured_quads(7, 5);
  for (const Eigen::Vector2d c : {Eigen::Vector2d(1.0, 0.6), Eigen::Vector2d(-0.3, 1.0), Eigen::Vector2d(1.0, 0.0)}) {
    CAPTURE(c.transpose());
    CHECK(upwind_order(m, c) == downwind_order(m, c));
  }
  CHECK(upwind_order(m, Eigen::Vector2d::Zero()).empty());
}

TEST_CASE("upwind order: topological where the centroid order is not (sheared cells)") {
  // Flow mostly down, slightly to the left: it crosses the 45-degree faces from each cell into
  // its right-hand neighbour, whose centroid lies further upstream along c.
  const Mesh m = sheared_grid();
  const Eigen::Vector2d c(-0.1, -1.0);
  const std::vector<int> centroids = downwind_order(m, c), up = upwind_order(m, c);
  REQUIRE(faces_against(m, centroids, c) > 50);  // the case the order is for
  CHECK(is_permutation_of_cells(m, up));
  CHECK(faces_against(m, up, c) == 0);

  // the adjoint's exact block sweep (downstream first) holds only in the topological order, and
  // dgsolve's block ILU is exact there: GMRES in at most 3 iterations
  const Case cs = parse_case(R"J({"exact": "sin(2*x+0.5)*cos(3*y-0.2)", "advection": [-0.1, -1.0]})J", "t.json");
  DGDiscretization dg(m, cs, 2);
  SparseMatrixCSC A;
  Eigen::VectorXd b, x;
  dg.assemble(A, b);
  const BlockSparseMatrix B(A, 9);
  double res = 1;
  CHECK_FALSE(solve_transposed_block_sweep(B, downwind_order(m, -c), b, x));
  REQUIRE(solve_transposed_block_sweep(B, upwind_order(m, -c), b, x, &res));
  CHECK(res < 1e-13);
  DGSolveOptions opt;
  opt.p = 2;
  const DGSolveResult r = dg_solve(m, cs, opt);
  CAPTURE(r.solve.solver);
  CHECK(r.solve.solver == "gmres-bilu0");
  CHECK(r.solve.iterations <= 3);
  CHECK(r.solve.relative_residual < 1e-13);
}

TEST_CASE("upwind order: a cycle (two non-convex cells) is broken, every cell once") {
  // A dart and the cell filling its notch share two edges; with c = (0, 1) the flow crosses one
  // from the dart into the other cell and the other back: a 2-cycle.
  Mesh m;
  m.nodes = {Vec2(0, 0), Vec2(2, 1), Vec2(0, 2), Vec2(1, 1), Vec2(-1, 1)};
  Cell dart, notch;
  dart.v = {0, 1, 2, 3};
  notch.v = {0, 3, 2, 4};
  m.cells = {dart, notch};
  const Eigen::Vector2d c(0, 1);
  const std::vector<int> up = upwind_order(m, c);
  CHECK(is_permutation_of_cells(m, up));
  CHECK(faces_against(m, up, c) == 1);  // one face of the cycle must go against the order
}
