// dg_solve end to end and the DG field "u" through an MSH file (coefficients bit-exact).
#include <doctest/doctest.h>

#include <cstdio>
#include <filesystem>
#include <unistd.h>
#include <string>

#include "case/case.hpp"
#include "core/error.hpp"
#include "dg/solve.hpp"
#include "dg_test_meshes.hpp"
#include "io/msh.hpp"

using namespace quadapt;

TEST_CASE("dg_solve: report figures and the field u survive write_msh/read_msh exactly") {
  Case cs = load_case(std::string(QUADAPT_SOURCE_DIR) + "/examples/cases/smooth.json");
  Mesh m = dgtest::half_split(make_perturbed_quads(6, 6, 0.2, 4));
  DGSolveOptions opt;
  opt.p = 3;
  DGSolveResult r = dg_solve(m, cs, opt);
  CHECK(r.dofs == m.num_cells() * 16);
  CHECK(r.hanging_faces == 12);  // 6 coarse edges on x = 1/2, each split in two faces
  CHECK(r.l2_error > 0);
  CHECK(r.l2_error < 1e-4);
  CHECK(r.has_functional);
  CHECK(r.functional_error < 1e-6);
  CHECK(r.solve.solver == "gmres-2level");  // auto with diffusion
  CHECK(r.solve.iterations > 0);
  CHECK(r.solve.relative_residual < 1e-11);

  Mesh out = m;
  out.set_field(make_dg_field(r.U, r.p, m.num_cells()));
  std::string path = (std::filesystem::temp_directory_path() / ("dg_field_" + std::to_string(::getpid()) + ".msh")).string();
  write_msh(out, path);
  Mesh back = read_msh(path);
  std::remove(path.c_str());
  std::remove((path + ".opt").c_str());  // write_msh writes Gmsh's view options beside a DG field
  const CellNodeField* f = back.cell_node_field("u");
  REQUIRE(f != nullptr);
  int p = 0;
  Eigen::VectorXd U = dg_field_coefficients(*f, p);
  CHECK(p == 3);
  CHECK(U == r.U);  // bit-exact
  // The re-read mesh gives the same discretisation (groups, hanging nodes).
  DGDiscretization dg(back, cs, 3);
  CHECK(dg.l2_error(U) == doctest::Approx(r.l2_error).epsilon(1e-14));

  CellNodeField bad = *f;
  bad.per_cell = 5;
  CHECK_THROWS_AS(dg_field_coefficients(bad, p), InputError);
  CHECK_THROWS_AS(make_dg_field(r.U, 2, m.num_cells()), InputError);
}

TEST_CASE("dg_solve: pure advection in downwind block order: block ILU is exact (up to single precision)") {
  // Upwind DG couples a cell only to its upwind neighbours: with the cells sorted along c the
  // matrix is block lower triangular and block ILU(0) is exact up to the single-precision
  // storage of its factors: every iteration gains ~7 digits, 3 reach the default 1e-14.
  Case cs = load_case(std::string(QUADAPT_SOURCE_DIR) + "/examples/cases/sshock-advection.json");
  Mesh m = make_structured_quads(12, 12);
  DGSolveOptions opt;
  opt.p = 2;
  DGSolveResult r = dg_solve(m, cs, opt);
  CHECK(r.solve.solver == "gmres-bilu0");
  CHECK(r.solve.iterations <= 3);
  CHECK(r.solve.relative_residual < 1e-13);
  opt.solver.kind = LinearSolverKind::UmfPack;
  DGSolveResult d = dg_solve(m, cs, opt);
  CHECK((r.U - d.U).norm() < 1e-11 * d.U.norm());
  // gmres-2level asked for explicitly runs here too (the coarse space is built whenever it is
  // asked for: needs_coarse_space; it used to throw "needs the mesh's coarse space")
  opt.solver.kind = LinearSolverKind::GmresTwoLevel;
  DGSolveResult t = dg_solve(m, cs, opt);
  CHECK(t.solve.solver == "gmres-2level");
  CHECK(t.solve.coarse_degree == 2);
  CHECK((t.U - d.U).norm() < 1e-11 * d.U.norm());
  CHECK_FALSE(needs_coarse_space(LinearSolverKind::Auto, true));
  CHECK(needs_coarse_space(LinearSolverKind::Auto, false));
  CHECK(needs_coarse_space(LinearSolverKind::GmresTwoLevel, true));
  CHECK_FALSE(needs_coarse_space(LinearSolverKind::GmresBlockILU, false));
}
