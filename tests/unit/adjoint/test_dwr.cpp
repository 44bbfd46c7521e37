// The DWR estimate of lib/adjoint/dwr.hpp (thesis eqs. 2.25-2.27; issue 4 "Done when"):
//  - the algebraic identity -psi^T R = J(u_h) - J(u_h^H) - int_Gamma (u_h - u_h^H)^2 against a
//    fine primal solve (sign convention, linearisation point, residual and adjoint assembly);
//  - zero residual and estimate when the exact solution is a degree-p polynomial;
//  - effectivity in [0.8, 1.25] on smooth cases for p = 1..3, conforming and 2:1 meshes;
//  - functional error rates: >= 2p - 0.3 with diffusion, >= 2p + 0.5 for pure advection;
//  - the transposed / re-ordered solves agree with a direct solve of A^T psi = g;
//  - bad input throws InputError.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "adjoint/block_sweep.hpp"
#include "adjoint/block_transpose.hpp"
#include "adjoint/dwr.hpp"
#include "case/case.hpp"
#include "core/error.hpp"
#include "dg/discretization.hpp"
#include "dg/linear_solver.hpp"
#include "dg/solve.hpp"
#include "mesh/mesh.hpp"
#include "refine/refine.hpp"

using namespace quadapt;

namespace {

// Diffusion + advection, natural (Neumann) functional boundary x = 1 whose end points meet the
// Dirichlet boundaries where u = 0 (sin(pi y)): the adjoint data are compatible at those corners,
// so the adjoint is smooth and the functional error is O(h^2p) (docs/adjoint.md).
const char* kDiffusion =
    R"J({"exact": "sin(pi*y)*(exp(x) + 0.5*cos(2*x-y))", "diffusion": [[0.3, 0.1], [0.1, 0.5]],
         "advection": [1.0, -0.7], "dirichlet": ["left", "top", "bottom"], "functional": {"boundary": "right"}})J";
// Pure advection, inflow data only; x = 1 is an outflow boundary.
const char* kAdvection =
    R"J({"exact": "sin(2*x+0.5)*cos(3*y-0.2) + exp(x*y)", "advection": [1.0, 0.6],
         "functional": {"boundary": "right"}})J";

Eigen::VectorXd primal(const Mesh& m, const Case& cs, int p, const DGOptions& dgo = {}) {
  DGDiscretization dg(m, cs, p, dgo);
  SparseMatrixCSC A;
  Eigen::VectorXd b;
  dg.assemble(A, b);
  LinearSolverOptions o;
  o.kind = LinearSolverKind::UmfPack;
  return solve_linear(A, b, o);
}

DWRResult dwr(const Mesh& m, const Case& cs, int p, const AdjointOptions& o = {}) {
  return compute_dwr(m, cs, primal(m, cs, p), p, o);
}

// A 2:1 non-conforming mesh: the n x n grid with the cells left of x = 0.4 (and their
// balance) split into four.
Mesh nonconforming(int n) {
  Mesh m = make_structured_quads(n, n);
  CellField ind;
  ind.name = "ind";
  for (int c = 0; c < m.num_cells(); ++c) ind.values.push_back(cell_centroid(m, c).x() < 0.4 ? 1.0 : 0.0);
  double frac = 0;
  for (double v : ind.values) frac += v;
  m.set_field(ind);
  RefineOptions o;
  o.mode = RefineOptions::Mode::Fraction;
  o.by = "ind";
  o.fraction = frac / m.num_cells();
  return refine_mesh(m, o);
}

}  // namespace

TEST_CASE("DWR identity: -psi^T R = J(u_h) - J(u_h^H) - int (u_h - u_h^H)^2, conforming and 2:1") {
  for (const char* js : {kDiffusion, kAdvection}) {
    const Case cs = parse_case(js, "t.json");
    for (int p = 1; p <= 2; ++p)
      for (int nc = 0; nc < 2; ++nc) {
        const Mesh m = nc ? nonconforming(4) : make_structured_quads(5, 4);
        const Eigen::VectorXd UH = primal(m, cs, p);
        AdjointOptions o;
        o.solver.kind = LinearSolverKind::UmfPack;
        const DWRResult r = compute_dwr(m, cs, UH, p, o);
        // the fine space's discretisation: the primal's SIPG penalty (fine_dg_options)
        const DGOptions fo = fine_dg_options({}, p);
        DGDiscretization fine(m, cs, p + 1, fo);
        const Eigen::VectorXd uh = primal(m, cs, p + 1, fo), uhH = fine.inject(UH, p);
        const double rhs = fine.functional(uh) - fine.functional(uhH) - fine.functional(uh - uhH);
        INFO("p=" << p << " nonconforming=" << nc << " estimate " << r.estimate << " vs " << rhs);
        CHECK(std::abs(r.estimate - rhs) <= 1e-10 * std::abs(rhs) + 1e-15);
        CHECK(r.functional == doctest::Approx(fine.functional(uhH)).epsilon(1e-14));
        // The estimate is the sum of the signed cell contributions; sum_eta bounds it.
        double s = 0;
        for (double e : r.eta_signed) s += e;
        CHECK(s == doctest::Approx(r.estimate).epsilon(1e-12));
        CHECK(r.sum_eta >= std::abs(r.estimate));
        CHECK(r.fine_dofs == static_cast<long long>(m.num_cells()) * (p + 2) * (p + 2));
      }
  }
}

TEST_CASE("DWR of a degree-p polynomial solution: zero residual, zero estimate, exact functional") {
  const Case cs = parse_case(
      R"J({"exact": "1 + 2*x - y + 0.5*x*y + 0.3*x*x*y - 0.2*y*y", "diffusion": [[0.3, 0.1], [0.1, 0.5]],
           "advection": [1.0, -0.7], "dirichlet": ["left", "top", "bottom"], "functional": {"boundary": "right"}})J",
      "t.json");
  const Mesh m = nonconforming(4);
  const DWRResult r = dwr(m, cs, 2);
  CHECK(r.residual.lpNorm<Eigen::Infinity>() < 1e-11);
  CHECK(std::abs(r.estimate) < 1e-12);
  CHECK(std::abs(r.functional_error) < 1e-12);
}

TEST_CASE("effectivity in [0.8, 1.25] on smooth cases, p = 1..3, conforming and 2:1") {
  for (const char* js : {kDiffusion, kAdvection}) {
    const Case cs = parse_case(js, "t.json");
    for (int p = 1; p <= 3; ++p)
      for (int nc = 0; nc < 2; ++nc) {
        const Mesh m = nc ? nonconforming(8) : make_structured_quads(8, 8);
        const DWRResult r = dwr(m, cs, p);
        INFO((js == kDiffusion ? "diffusion" : "advection") << " p=" << p << " nonconforming=" << nc << ": error "
                                                            << r.functional_error << ", estimate " << r.estimate);
        CHECK(r.effectivity >= 0.8);
        CHECK(r.effectivity <= 1.25);
        // The adjoint-corrected functional is closer to J(u) than J_H(u_H).
        CHECK(std::abs(r.functional_exact - r.corrected) < 0.25 * std::abs(r.functional_error));
      }
  }
}

TEST_CASE("functional error rates: 2p with diffusion, 2p+1 for pure advection") {
  struct Run {
    const char* js;
    const char* name;
    double margin;  // required rate = 2p + margin
  };
  for (Run run : {Run{kDiffusion, "diffusion", -0.3}, Run{kAdvection, "advection", 0.5}}) {
    const Case cs = parse_case(run.js, "t.json");
    for (int p = 1; p <= 3; ++p) {
      const int n = p == 1 || run.js == kAdvection ? 8 : 4;
      const DWRResult a = dwr(make_structured_quads(n, n), cs, p);
      const DWRResult b = dwr(make_structured_quads(2 * n, 2 * n), cs, p);
      const double rate = std::log2(std::abs(a.functional_error / b.functional_error));
      const double est_rate = std::log2(std::abs(a.estimate / b.estimate));
      INFO(run.name << " p=" << p << " n=" << n << ": |J - J_H| " << a.functional_error << " -> "
                    << b.functional_error << ", rate " << rate << "; estimate rate " << est_rate);
      CHECK(rate >= 2 * p + run.margin);
      CHECK(est_rate >= 2 * p + run.margin);
    }
  }
}

TEST_CASE("adjoint solves agree: every solver and elimination order vs UMFPACK on Eigen's transpose") {
  const Case adv = parse_case(kAdvection, "t.json"), dif = parse_case(kDiffusion, "t.json");
  const Mesh m = nonconforming(6);
  for (const Case* cs : {&adv, &dif}) {
    const int p = 2;
    DGDiscretization fine(m, *cs, p + 1);
    SparseMatrixCSC A;
    BlockSparseMatrix B;
    Eigen::VectorXd b;
    fine.assemble(A, b);
    fine.assemble(B, b);
    const Eigen::VectorXd g = fine.functional_gradient(fine.inject(primal(m, *cs, p), p));
    SparseMatrixCSC At = A.transpose();
    LinearSolverOptions d;
    d.kind = LinearSolverKind::UmfPack;
    const Eigen::VectorXd ref = solve_linear(At, g, d);
    for (LinearSolverKind k : {LinearSolverKind::Auto, LinearSolverKind::UmfPack, LinearSolverKind::GmresBlockILU,
                               LinearSolverKind::GmresTwoLevel})
      for (AdjointOrdering ord : {AdjointOrdering::Auto, AdjointOrdering::Flow, AdjointOrdering::Mesh}) {
        AdjointOptions o;
        o.solver.kind = k;
        o.ordering = ord;
        o.fallback_direct = false;
        LinearSolveInfo info;
        const Eigen::VectorXd psi = solve_adjoint(B, g, m, p + 1, cs->advection, cs->advection_only(), o, &info);
        INFO(info.solver << " ordering " << static_cast<int>(ord) << ": " << info.iterations << " iterations");
        CHECK((psi - ref).norm() <= 1e-9 * ref.norm());
        // Pure advection, downstream first: A^T is block triangular, ILU(0) exact, and auto
        // solves it by one block sweep.
        if (cs == &adv && ord == AdjointOrdering::Flow && k == LinearSolverKind::GmresBlockILU)
          CHECK(info.iterations <= 2);
        if (cs == &adv && ord != AdjointOrdering::Mesh && k == LinearSolverKind::Auto) CHECK(info.solver == "block-sweep");
      }
  }
}

TEST_CASE("cell indicators: the fine form on the primal's space is the primal's (cellwise Galerkin orthogonality)") {
  // u_H solves the degree-p problem, so R_h(u_H)(v_H) = 0 for every v_H of degree p on one cell
  // when the fine space's form restricted to degree p is the primal's: the part I_H psi of the
  // weight (psi interpolated to degree p, cell by cell) adds nothing to any cell's eta_k. With
  // the fine space's own SIPG penalty it did, in cancelling pairs: sum_eta / |estimate| was
  // 1e3-1e4 on natural functional boundaries (docs/adjoint.md, "Cell indicators").
  const Case cs = parse_case(kDiffusion, "t.json");  // functional on the natural boundary x = 1
  for (int p = 1; p <= 3; ++p)
    for (int nc = 0; nc < 2; ++nc) {
      const Mesh m = nc ? nonconforming(6) : make_structured_quads(7, 6);
      const DWRResult r = dwr(m, cs, p);
      DGDiscretization coarse(m, cs, p), fine(m, cs, p + 1, fine_dg_options({}, p));
      const Eigen::VectorXd Ipsi = fine.inject(coarse.inject(r.psi, p + 1), p);  // I_H psi at the fine nodes
      const int nb = (p + 2) * (p + 2);
      double coarse_part = 0;
      for (int k = 0; k < m.num_cells(); ++k) {
        // cells on a Dirichlet side (left, top, bottom) keep the fine space's own penalty on that
        // face (fine_dg_options): their boundary mismatch is a true local term
        bool dirichlet = false;
        for (int v : m.cells[k].v)
          if (v >= 0 && (m.nodes[v].x() == 0 || m.nodes[v].y() == 0 || m.nodes[v].y() == 1)) dirichlet = true;
        if (!dirichlet)
          coarse_part = std::max(coarse_part, std::abs(Ipsi.segment(k * nb, nb).dot(r.residual.segment(k * nb, nb))));
      }
      const double eta_max = *std::max_element(r.eta.begin(), r.eta.end());
      INFO("p=" << p << " nonconforming=" << nc << ": max over interior cells |(I_H psi)_k . R_k| " << coarse_part << ", max eta "
                << eta_max << ", sum_eta " << r.sum_eta << ", estimate " << r.estimate);
      CHECK(coarse_part <= 1e-4 * eta_max);  // the finer quadrature: 1e-6..4e-6 measured
      CHECK(r.sum_eta <= 20 * std::abs(r.estimate));
    }
}

TEST_CASE("the file's cell order does not slow the adjoint: auto orders the cells along the flow") {
  // Adapted meshes come in an arbitrary cell order. With the block ILU in the file's order
  // (auto's choice with diffusion before) the S-shock goal loop's adjoint took 46-229
  // gmres-2level iterations against 16-22 in the flow order, and an advection-dominated case
  // fell back to UMFPACK (docs/adjoint.md, Solver). Here: the same grid with its cells shuffled.
  const char* kSteep =
      R"J({"exact": "tanh(10*(x + y - 1))", "diffusion": [[0.01, 0], [0, 0.01]], "advection": [1.0, 1.0],
           "dirichlet": ["left", "top", "bottom", "right"], "functional": {"boundary": "right"}})J";
  const char* kLaplace = R"J({"exact": "sin(pi*x)*exp(y)", "diffusion": [[1, 0], [0, 1]],
           "dirichlet": ["left", "top", "bottom", "right"], "functional": {"boundary": "right"}})J";
  for (const char* js : {kDiffusion, kSteep, kLaplace}) {
    const Case cs = parse_case(js, "t.json");
    const Mesh m = make_structured_quads(24, 24);
    Mesh shuffled = m;
    const int n = m.num_cells();
    for (int i = 0; i < n; ++i) shuffled.cells[i] = m.cells[(7 * i + 3) % n];  // gcd(7, 576) = 1
    const int p = 2;
    const DWRResult a = dwr(m, cs, p), b = dwr(shuffled, cs, p);
    INFO(js << "\ngrid order: " << a.solve.solver << " " << a.solve.iterations << " iterations; shuffled: "
            << b.solve.solver << " " << b.solve.iterations);
    CHECK(a.solve.solver == "gmres-2level");
    CHECK(b.solve.solver == "gmres-2level");
    // the same geometric order up to ties between equal centroids: the same iterations within 2
    CHECK(std::abs(a.solve.iterations - b.solve.iterations) <= 2);
    CHECK(b.estimate == doctest::Approx(a.estimate).epsilon(1e-7));
  }
}

TEST_CASE("block sweep: exact for triangular A^T, refuses otherwise") {
  const Case adv = parse_case(kAdvection, "t.json"), dif = parse_case(kDiffusion, "t.json");
  const Mesh m = nonconforming(5);
  for (const Case* cs : {&adv, &dif}) {
    DGDiscretization dg(m, *cs, 2);
    SparseMatrixCSC A;
    Eigen::VectorXd b, x;
    dg.assemble(A, b);
    const BlockSparseMatrix B(A, 9);
    const std::vector<int> down = downwind_order(m, -cs->advection), up = downwind_order(m, cs->advection);
    double res = 1;
    if (cs == &adv) {
      REQUIRE(solve_transposed_block_sweep(B, down, b, x, &res));
      CHECK(res < 1e-13);
      SparseMatrixCSC At = A.transpose();
      CHECK((At * x - b).norm() <= 1e-12 * b.norm());
      CHECK_FALSE(solve_transposed_block_sweep(B, up, b, x));  // upstream first: not triangular
    } else {
      CHECK_FALSE(solve_transposed_block_sweep(B, down, b, x));  // diffusion couples both ways
    }
  }
}

TEST_CASE("block_transpose and transpose_in_place give A^T") {
  const Case cs = parse_case(kDiffusion, "t.json");
  const Mesh m = nonconforming(3);
  DGDiscretization dg(m, cs, 1);
  SparseMatrixCSC A;
  Eigen::VectorXd b;
  dg.assemble(A, b);
  const BlockSparseMatrix T = block_transpose(BlockSparseMatrix(A, 4));
  const Eigen::MatrixXd Ad = Eigen::MatrixXd(A), Td = Eigen::MatrixXd(T.to_csc());
  CHECK(Td.rows() == Ad.cols());
  CHECK((Td - Ad.transpose()).cwiseAbs().maxCoeff() == 0.0);
  for (int I = 0; I < T.block_rows(); ++I)
    for (long long k = T.row_start()[I] + 1; k < T.row_start()[I + 1]; ++k) CHECK(T.cols()[k - 1] < T.cols()[k]);
  BlockSparseMatrix S(A, 4);
  REQUIRE(transpose_in_place(S));
  CHECK((Eigen::MatrixXd(S.to_csc()) - Ad.transpose()).cwiseAbs().maxCoeff() == 0.0);
  // A pattern that is not symmetric is refused and left alone.
  BlockSparseMatrix U(2, {0, 2, 3}, {0, 1, 1});
  U.block(1)[0] = 7;
  CHECK_FALSE(transpose_in_place(U));
  CHECK(U.block(1)[0] == 7);
}

TEST_CASE("bad input: no functional, unknown boundary, wrong vector, missing field") {
  const Mesh m = make_structured_quads(3, 3);
  const Case nofun = parse_case(R"J({"exact": "x", "advection": [1, 0]})J", "nofun.json");
  CHECK_THROWS_AS(compute_dwr(m, nofun, Eigen::VectorXd::Zero(36), 1), InputError);
  const Case badb = parse_case(R"J({"exact": "x", "advection": [1, 0], "functional": {"boundary": "outlet"}})J", "b.json");
  try {
    compute_dwr(m, badb, Eigen::VectorXd::Zero(36), 1);
    FAIL("no exception");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("outlet") != std::string::npos);
  }
  const Case ok = parse_case(kAdvection, "t.json");
  CHECK_THROWS_AS(compute_dwr(m, ok, Eigen::VectorXd::Zero(35), 1), InputError);
  int p = 0;
  try {
    read_solution_field(m, "u", "sol.msh", p);
    FAIL("no exception");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("sol.msh") != std::string::npos);
    CHECK(std::string(e.what()).find("'u'") != std::string::npos);
  }
  Mesh m2 = m;
  CellNodeField f;
  f.name = "u";
  f.degree = 2;
  f.per_cell = 9;
  f.values.assign(9 * 9, 0.5);
  m2.set_field(f);
  const Eigen::VectorXd U = read_solution_field(m2, "u", "sol.msh", p);
  CHECK(p == 2);
  CHECK(U.size() == 81);
  m2.cell_node_field("u")->values[3] = NAN;
  CHECK_THROWS_AS(read_solution_field(m2, "u", "sol.msh", p), InputError);
}
