// The curved (high-order) cell map: area, normals and Jacobian positivity (issue #18, "Done
// when" 3). The reference values are computed independently of mesh/curved.cpp: the area of a
// polynomial map by the boundary integral 1/2 of the closed curve integral of (x dy - y dx)
// with a Lagrange interpolant written out here, the disk by pi R^2.
#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include "case/case.hpp"
#include "core/error.hpp"
#include "curved_disk.hpp"
#include "dg/discretization.hpp"
#include "fem/basis.hpp"
#include "mesh/curved.hpp"
#include "mesh/validate.hpp"
#include "../worst.hpp"

using namespace quadapt;
using curvedtest::curved_disk;

namespace {

// 8-point Gauss-Legendre on [-1, 1] (exact for degree 15 >= 2q - 1 with q <= 6).
const Rule1D gauss8 = gauss_legendre(8);

// Independent 1D Lagrange interpolation through P[0..q] at s_k = k/q: value and derivative.
void curve(const std::vector<Vec2>& P, double s, Vec2& x, Vec2& dx) {
  const int q = static_cast<int>(P.size()) - 1;
  x.setZero();
  dx.setZero();
  for (int k = 0; k <= q; ++k) {
    double l = 1, dl = 0;
    for (int m = 0; m <= q; ++m) {
      if (m == k) continue;
      const double den = double(k - m) / q;
      dl = dl * (s - double(m) / q) / den + l / den;
      l *= (s - double(m) / q) / den;
    }
    x += l * P[k];
    dx += dl * P[k];
  }
}

// The control points of boundary edge v[1] -> v[2] (local edge 1) of cell c.
std::vector<Vec2> edge1_points(const Mesh& m, int c) {
  const int q = m.geometric_order();
  std::vector<Vec2> P;
  for (int b = 0; b <= q; ++b) P.push_back(m.cell_points(c)[q + (q + 1) * b]);
  return P;
}

// Area enclosed by the boundary: 1/2 closed integral of (x dy - y dx) along the boundary edges.
double boundary_area(const Mesh& m) {
  double A = 0;
  for (int c = 0; c < m.num_cells(); ++c) {
    bool on = false;
    for (const BoundaryEdge& be : m.boundary) on = on || (be.v[0] == m.cells[c].v[1] && be.v[1] == m.cells[c].v[2]);
    if (!on) continue;
    const std::vector<Vec2> P = edge1_points(m, c);
    for (int k = 0; k < 8; ++k) {
      Vec2 x, dx;
      curve(P, 0.5 * (gauss8.x[k] + 1), x, dx);
      A += 0.25 * gauss8.w[k] * (x.x() * dx.y() - x.y() * dx.x());
    }
  }
  return A;
}

double rate(double e0, double e1) { return std::log2(e0 / e1); }

/// validate_mesh's refusal of m (read as `name`): its message, or "no error" when it accepts m.
std::string refusal(const Mesh& m, const std::string& name, bool allow_curved = true) {
  ValidateOptions v;
  v.allow_curved = allow_curved;
  try {
    validate_mesh(m, name, v);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST_CASE("curved map: disk area at q = 3 equals the polynomial map's own area to 1e-12; converges to pi") {
  // What "area to 1e-12" means: a q = 3 polynomial map does not reproduce a circle, so the
  // reference is the exact area of the polynomial region, computed from its boundary curves.
  for (int q : {2, 3, 4, 5, 6}) {
    for (int n : {1, 2}) {
      CAPTURE(q);
      const Mesh m = curved_disk(n, q);
      const double Ab = boundary_area(m);
      CHECK(std::abs(total_area(m) - Ab) < 1e-12);
      // The DG geometry: ||0 - 1||_L2^2 = integral of 1 over the curved cells.
      Case one = parse_case(R"J({"diffusion": [[1, 0], [0, 1]], "exact": "1"})J", "one.json");
      DGDiscretization dg(m, one, q);
      const double e = dg.l2_error(Eigen::VectorXd::Zero(dg.num_dofs()));
      CHECK(std::abs(e * e - Ab) < 1e-12);
    }
  }
  // Convergence to the disk: |A_h - pi| = O(h^(q+1)) for odd q, O(h^(q+2)) for even q (the
  // interpolation error's leading term integrates to zero along each edge for even q).
  // Measured on n = 2, 4, 8: q = 1 rates 1.97, 1.99; q = 2: 3.98, 4.00; q = 3: 3.95, 3.99;
  // q = 4: 5.98, 5.99; q = 5: 5.94, 5.99; q = 6: 7.98, 8.23 (3.98e-9, 1.58e-11, 5.2e-14).
  for (int q : {1, 2, 3, 4, 5, 6}) {
    double prev = 0;
    for (int n : {2, 4, 8}) {
      CAPTURE(q);
      const double err = std::abs(total_area(curved_disk(n, q)) - M_PI);
      if (n > 2) CHECK(rate(prev, err) > (q % 2 ? q + 1 : q + 2) - 0.1);
      prev = err;
    }
  }
}

TEST_CASE("curved map: edge normals — closed-curve identities to rounding, radial to O(h^q)") {
  for (int q : {2, 3}) {
    double prev = 0;
    for (int n : {1, 2, 4, 8}) {
      const Mesh m = curved_disk(n, q);
      Vec2 sum_n = Vec2::Zero();
      double flux = 0, worst = 0;
      for (int c = 0; c < m.num_cells(); ++c) {
        const CellMap G(m, c);
        for (int e = 0; e < 4; ++e) {
          // Boundary edges only: local edge 1 of the ring cells at the circle.
          const int a = m.cells[c].v[e], b = m.cells[c].v[(e + 1) % 4];
          bool on = false;
          for (const BoundaryEdge& be : m.boundary) on = on || (be.v[0] == a && be.v[1] == b);
          if (!on) continue;
          for (int k = 0; k < 8; ++k) {
            Vec2 x, nrm;
            const double ds = edge_geometry(G, e, 0.5 * (gauss8.x[k] + 1), x, nrm);
            CHECK(std::abs(nrm.norm() - 1) < 1e-14);
            sum_n += 0.5 * gauss8.w[k] * ds * nrm;
            flux += 0.5 * gauss8.w[k] * ds * x.dot(nrm);
            worst = quadapt_test::worst_of(worst, std::acos(std::min(1.0, nrm.dot(x.normalized()))));
          }
        }
      }
      CHECK(sum_n.norm() < 1e-14);                            // closed curve: integral of n = 0
      CHECK(std::abs(flux - 2 * boundary_area(m)) < 1e-12);  // divergence theorem: x . n = 2 |A|
      // Measured rates (n = 1..8): q = 2: 2.78, 2.94, 2.98; q = 3: 2.83, 2.96, 2.99.
      if (n > 1) CHECK(rate(prev, worst) > q - 0.25);
      prev = worst;
    }
  }
}

TEST_CASE("curved map: Jacobian positivity — valid disks, a folded cell rejected") {
  for (int q : {2, 3})
    for (int n : {1, 4}) {
      const Mesh m = curved_disk(n, q);
      const ScaledJacobian sj = min_scaled_jacobian(m);
      CHECK(sj.min > 0.2);  // measured 0.27 (q = 3) to 0.30
      ValidateOptions v;
      v.allow_curved = true;
      CHECK_NOTHROW(validate_mesh(m, "disk.msh", v));
    }
  Mesh m = curved_disk(1, 3);
  // Tools that have not been taught the curved map refuse it.
  CHECK(refusal(m, "disk.msh", false).find("disk.msh: the mesh has curved cells (geometric order 3)") != std::string::npos);
  // Pull the first edge-interior point of cell 0's outer edge deep into the cell: the map folds.
  Vec2* X = m.curved.points.data();
  X[3 + 4 * 1] = m.nodes[m.cells[0].v[0]] + Vec2(-0.2, 0.0);
  CHECK(min_scaled_jacobian(m).min <= 0);
  CHECK(refusal(m, "folded.msh").find("non-positive Jacobian") != std::string::npos);
  Case one = parse_case(R"J({"diffusion": [[1, 0], [0, 1]], "exact": "1"})J", "one.json");
  CHECK_THROWS_AS(DGDiscretization(m, one, 3), InputError);
}

TEST_CASE("curved map: neighbours whose curved edges differ are refused by the DG") {
  Mesh m = curved_disk(1, 2);
  // Cell 4 is the centre square; move the midpoint of its edge 1 (shared with cell 0) in cell 4
  // only: the two sides no longer trace the same curve.
  m.curved.points[4 * 9 + 2 + 3 * 1] += Vec2(0.01, 0);
  Case one = parse_case(R"J({"diffusion": [[1, 0], [0, 1]], "exact": "1"})J", "one.json");
  try {
    DGDiscretization dg(m, one, 2);
    FAIL("no error");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("share the edge") != std::string::npos);
  }
  m.curved.points[4 * 9 + 2 + 3 * 1] -= Vec2(0.01, 0);
  CHECK_NOTHROW(DGDiscretization(m, one, 2));
}

TEST_CASE("curved map: a fold between the sample points is found (det J certified by Bernstein bounds)") {
  // Cell [0, 0.5]^2 at q = 3 with its bottom edge's two inner nodes pushed together along the edge,
  // to x = 0.25 -+ 0.00556: x(xi) on that edge runs backwards for |xi| < 0.126, so det J < 0 there
  // (-3.1e-3 on a 401^2 grid) while it is positive at all 8 x 8 sample points (+8.9e-4: a review's
  // construction; meshquality said 0.70, dgsolve solved it with 27x the error).
  auto make = [](double spread) {
    Mesh m = make_structured_quads(1, 1, 0, 0.5, 0, 0.5);
    elevate_geometric_order(m, 3);
    m.curved.points[1] = Vec2(0.25 - spread, 0);
    m.curved.points[2] = Vec2(0.25 + spread, 0);
    return m;
  };
  const Mesh folded = make(0.00556), fine = make(0.05);
  // the 8 x 8 samples alone: all positive
  CellMap G(folded, 0);
  double lo = 1e300;
  Vec2 t1, t2;
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 8; ++i) lo = std::min(lo, G.jacobian(-1 + 2.0 * i / 7, -1 + 2.0 * j / 7, t1, t2));
  CHECK(lo > 0);
  const JacobianCertificate cert = certify_jacobian(folded, 0);
  CHECK_FALSE(cert.positive);
  CHECK(cert.lowest < 0);
  // the witness is det J at a point of the cell: it is below zero there
  MESSAGE("folded: sampled min " << lo << ", certificate's point value " << cert.lowest);
  CHECK(min_scaled_jacobian(folded).min <= 0);
  ValidateOptions v;
  v.allow_curved = true;
  CHECK(refusal(folded, "folded.msh").find("non-positive Jacobian") != std::string::npos);
  // an unfolded cell is certified, and keeps its sampled scaled Jacobian
  CHECK(certify_jacobian(fine, 0).positive);
  CHECK(min_scaled_jacobian(fine).min > 0);
  CHECK_NOTHROW(validate_mesh(fine, "fine.msh", v));
  // the Bernstein conversion: on a disk of every order the certificate agrees with the samples
  // (valid), and its lowest value — the smallest corner coefficient, which a right conversion of
  // the 2q x 2q values makes det J at the cell's corners — is det J's minimum over the 4 corners
  for (int q : {2, 3, 4, 6}) {
    const Mesh d = curved_disk(2, q);
    for (int c = 0; c < d.num_cells(); ++c) {
      const JacobianCertificate cc = certify_jacobian(d, c);
      CHECK(cc.positive);
      CellMap Gd(d, c);
      double corners = 1e300;
      for (double xi : {-1.0, 1.0})
        for (double eta : {-1.0, 1.0}) corners = std::min(corners, Gd.jacobian(xi, eta, t1, t2));
      CHECK(cc.lowest == doctest::Approx(corners).epsilon(1e-9));
    }
  }
}

TEST_CASE("curved map: det J's sign decided to 1e-5 of its scale, either way") {
  // Cell [0, 0.5]^2 at q = 3 whose bottom edge is a cubic x(xi) (y = 0) whose slope x'(xi) is
  // smallest, = m, at xi = 0.3 (a review's construction): m = +1e-5 is valid (det J > 0, 1e-5 of its
  // largest), m = -1e-5 is a fold. The certificate's first depth limit (12) called the first a fold.
  auto make = [](double m) {
    const double xs = 0.3, A = (0.25 - m) / (1 + 3 * xs * xs), a3 = A, a2 = -3 * A * xs, a1 = 0.25 - A, a0 = 0.25 - a2;
    auto x = [&](double t) { return a0 + a1 * t + a2 * t * t + a3 * t * t * t; };
    Mesh c = make_structured_quads(1, 1, 0, 0.5, 0, 0.5);
    elevate_geometric_order(c, 3);
    c.curved.points[1] = Vec2(x(-1.0 / 3), 0);
    c.curved.points[2] = Vec2(x(1.0 / 3), 0);
    return c;
  };
  ValidateOptions v;
  v.allow_curved = true;
  const Mesh valid = make(1e-5), folded = make(-1e-5);
  const JacobianCertificate a = certify_jacobian(valid, 0), b = certify_jacobian(folded, 0);
  CHECK(a.positive);
  CHECK(min_scaled_jacobian(valid).min > 0);
  CHECK_NOTHROW(validate_mesh(valid, "valid.msh", v));
  CHECK_FALSE(b.positive);
  CHECK(b.lowest < 0);
  CHECK_THROWS_AS(validate_mesh(folded, "folded.msh", v), InputError);
}

TEST_CASE("curved map: a cell folded through itself is called inverted, not zero-area") {
  // q = 2, the bottom edge's middle node pulled past the top edge: signed area -0.0167 (it said
  // "degenerate: zero area"; a review)
  Mesh m = make_structured_quads(1, 1, 0, 0.5, 0, 0.5);
  elevate_geometric_order(m, 2);
  m.curved.points[1] = Vec2(0.25, 0.8);
  const std::string msg = refusal(m, "fold.msh");
  MESSAGE(msg);
  CHECK(msg.find("inverted: its curved map folds (signed area -1.667e-02 < 0)") != std::string::npos);
}
