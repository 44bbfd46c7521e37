#include <doctest/doctest.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <random>
#include <sstream>

#include "../estimate/test_util.hpp"
#include "core/error.hpp"
#include "estimate/estimate_frame.hpp"
#include "estimate/interpolate.hpp"
#include "mesh/topology.hpp"
#include "frame/frame.hpp"
#include "sizing/size_frame.hpp"
#include "sizing/size_field.hpp"

using namespace quadapt;

namespace {
Mesh shape_of(Mesh m, int p, const std::function<double(double, double)>& f, EstimateOptions o = {}) {
  m.set_field(interpolate_dg(m, p, f));
  return make_shape_mesh(m, estimate_frame(m, o));
}
double sshock(double x, double y) { return 0.75 * std::tanh(4 * std::sin(10 * y - 5) - 24 * x + 12); }
double spread(const std::vector<double>& v) {
  auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  return (*hi - *lo) / *hi;
}
}  // namespace

TEST_CASE("feature-based: complexity met and the optimality condition holds in every cell") {
  for (int p = 1; p <= 3; ++p)
    for (double q : {1.0, 2.0}) {
      CAPTURE(p);
      CAPTURE(q);
      // a smooth function whose (p+1)-th derivatives vanish nowhere on the domain
      Mesh s = shape_of(make_perturbed_quads(12, 12, 0.25, 3), p,
                        [](double x, double y) { return std::exp(1.5 * x + 0.7 * y) + std::exp(-x - 2 * y); });
      SizeOptions o;
      o.complexity = 3000;
      o.q = q;
      o.hmax = 100;   // bounds far away: no safeguard active
      o.hmin = 1e-9;
      o.max_anisotropy = 1e9;
      SizeResult r = solve_feature_size(s, o);
      CHECK(r.cells_at_hmax == 0);
      CHECK(r.cells_at_hmin == 0);
      CHECK(r.continuous_complexity == doctest::Approx(3000).epsilon(1e-9));
      const int n = p + 1;
      std::vector<double> opt;
      for (int k = 0; k < s.num_cells(); ++k) {
        REQUIRE(r.B[k] > 0);
        opt.push_back(r.B[k] * std::pow(r.d[k], -(q * n + 2) / 2));
        CHECK(r.h[k] == doctest::Approx(0.5 / std::sqrt(r.d[k])));
      }
      CHECK(spread(opt) < 1e-9);
      // and the constant is 2 λ n / q (stationarity of the Lagrangian, eq. 5.20)
      CHECK(opt[0] == doctest::Approx(2 * r.lambda * n / q).epsilon(1e-9));
    }
}

TEST_CASE("density exponent: d ∝ B^(2/(q(p+1)+2)) (corrected eq. 5.21)") {
  // two cells, synthetic shape fields, no A1/A2: the density ratio follows the corrected exponent
  Mesh m = make_structured_quads(2, 1);
  auto set = [&](const char* n, std::vector<double> v) { CellField f; f.name = n; f.values = v; m.set_field(f); };
  set("theta", {0, 0});
  set("rho", {1, 1});
  set("B", {1.0, 1e-6});
  set("p", {2, 2});
  SizeOptions o;
  o.complexity = 900;
  o.hmax = 100;
  o.hmin = 1e-9;
  SizeResult r = solve_feature_size(m, o);
  const double e = 2.0 / (2 * 3 + 2);
  CHECK(r.d[0] / r.d[1] == doctest::Approx(std::pow(1e6, e)).epsilon(1e-10));
  CHECK(r.continuous_complexity == doctest::Approx(900).epsilon(1e-10));
}

TEST_CASE("safeguards: size bounds and gradation active, complexity still met") {
  Mesh s = shape_of(make_structured_quads(16, 16), 2, sshock);
  SizeOptions o;
  o.complexity = 1.5 * 256 * 9;
  SizeResult free = solve_feature_size(s, o);
  CHECK(free.continuous_complexity == doctest::Approx(o.complexity).epsilon(1e-9));
  CHECK(free.cells_at_hmax > 0);  // default hmax caps the flat regions (B ~ 0 there)
  double hmin_free = *std::min_element(free.h.begin(), free.h.end());
  // force a minimum size larger than the free optimum's smallest
  o.hmin = 1.5 * hmin_free;
  SizeResult clamped = solve_feature_size(s, o);
  CHECK(clamped.cells_at_hmin > 0);
  CHECK(clamped.continuous_complexity == doctest::Approx(o.complexity).epsilon(1e-9));
  for (int k = 0; k < s.num_cells(); ++k) {
    // every half-axis within the bounds: h2 = h/sqrt(rho) >= hmin, h1 = h sqrt(rho) <= hmax
    CHECK(clamped.h[k] / std::sqrt(clamped.rho[k]) >= o.hmin * (1 - 1e-12));
    CHECK(clamped.h[k] * std::sqrt(clamped.rho[k]) <= clamped.hmax * (1 + 1e-12));
  }
  // gradation 1.5 between face neighbours
  o.hmin = 0;
  o.gradation = 1.5;
  SizeResult g = solve_feature_size(s, o);
  CHECK(g.cells_graded > 0);
  CHECK(g.continuous_complexity == doctest::Approx(o.complexity).epsilon(1e-9));
  Topology t = build_topology(s);
  for (int k = 0; k < s.num_cells(); ++k)
    for (int j : t.neighbours(k)) CHECK(g.h[k] <= 1.5 * g.h[j] * (1 + 1e-12));
  // anisotropy cap
  o.gradation = 0;
  o.max_anisotropy = 3;
  SizeResult a = solve_feature_size(s, o);
  CHECK(a.cells_anisotropy_capped > 0);
  for (double rho : a.rho) CHECK(rho <= 3 + 1e-12);
  CHECK(a.continuous_complexity == doctest::Approx(o.complexity).epsilon(1e-9));
}

TEST_CASE("size-solve bad targets: clear errors") {
  Mesh s = shape_of(make_structured_quads(8, 8), 2, sshock);
  SizeOptions o;
  o.complexity = 100;  // less than 16 p = 2 elements (the default hmax = 0.125 sqrt(area))
  CHECK_THROWS_WITH_AS(solve_feature_size(s, o, "shape.msh"), doctest::Contains("below the smallest"), InputError);
  o.complexity = 1e9;
  o.hmin = 0.01;  // at most 2500 elements of p = 2
  CHECK_THROWS_WITH_AS(solve_feature_size(s, o, "shape.msh"), doctest::Contains("exceeds"), InputError);
  o.complexity = -1;
  CHECK_THROWS_AS(solve_feature_size(s, o), InputError);
  // missing fields
  Mesh bare = make_structured_quads(4, 4);
  o.complexity = 100;
  o.hmin = 0;
  CHECK_THROWS_WITH_AS(solve_feature_size(bare, o, "x.msh"), doctest::Contains("x.msh: no cell field"), InputError);
}

TEST_CASE("frame M = V^-1 (eq. 3.13) and the Vinv layout") {
  const double h = 0.02, rho = 9, th = 0.6;
  Eigen::Matrix2d M = frame_inverse(h, rho, th);
  const double h1 = h * 3, h2 = h / 3;
  Eigen::Vector2d v(h1 * std::cos(th), h1 * std::sin(th)), w(-h2 * std::sin(th), h2 * std::cos(th));
  CHECK((M * v - Eigen::Vector2d(1, 0)).norm() < 1e-12);
  CHECK((M * w - Eigen::Vector2d(0, 1)).norm() < 1e-12);
  CHECK(1 / M.determinant() == doctest::Approx(h * h));  // det V = h1 h2 = h^2
  auto c = vinv_components(M);
  CHECK(c[0] == M(0, 0));
  CHECK(c[1] == M(0, 1));
  CHECK(c[3] == M(1, 0));
  CHECK(c[4] == M(1, 1));
  for (int i : {2, 5, 6, 7, 8}) CHECK(c[i] == 0);
}

TEST_CASE("frame layout agrees with PHiLiP's Vinv (fixture input_ss15_fb_p2_3.msh)") {
  // PHiLiP writes M = diag(1/h1, 1/h2) R(-θ) row-major (its second row may carry a reflection,
  // harmless for a frame ⟨v, w, -v, -w⟩). Decode each row set into (h, ρ, θ) and rebuild it.
  std::ifstream in(std::string(QUADAPT_FIXTURES_DIR) + "/input_ss15_fb_p2_3.msh");
  REQUIRE(in.good());
  std::string line;
  while (std::getline(in, line) && line != "$ElementData") {}
  for (int i = 0; i < 8 && std::getline(in, line);) {  // skip the view header (tags)
    if (line.find(' ') != std::string::npos) break;
  }
  int checked = 0;
  do {
    std::istringstream ss(line);
    double tag, a[9];
    ss >> tag;
    for (double& x : a) ss >> x;
    if (!ss) break;
    const double r1 = std::hypot(a[0], a[1]), r2 = std::hypot(a[3], a[4]);
    const double h1 = 1 / r1, h2 = 1 / r2, th = std::atan2(a[1], a[0]);
    Eigen::Matrix2d M = frame_inverse(std::sqrt(h1 * h2), h1 / h2, th);
    CHECK(M(0, 0) == doctest::Approx(a[0]).epsilon(1e-9));
    CHECK(M(0, 1) == doctest::Approx(a[1]).epsilon(1e-9));
    CHECK(std::abs(M(1, 0)) == doctest::Approx(std::abs(a[3])).epsilon(1e-5));
    CHECK(std::abs(M(1, 1)) == doctest::Approx(std::abs(a[4])).epsilon(1e-5));
    // PHiLiP stores some frames reflected (row 2 negated), hence the abs() above; the rows are
    // still perpendicular, which abs() alone does not check (a test audit, session 38)
    CHECK(std::abs(a[0] * a[3] + a[1] * a[4]) < 1e-5 * r1 * r2);
    for (int i : {2, 5, 6, 7, 8}) CHECK(a[i] == 0);
    ++checked;
  } while (std::getline(in, line) && line != "$EndElementData");
  CHECK(checked == 800);
}

TEST_CASE("tanh(50x) end to end: the frame's parallelogram is thin in x") {
  Mesh s = shape_of(testutil::rescale(make_perturbed_quads(32, 32, 0.2, 5), -0.5, 0.5, -0.5, 0.5), 2,
                    [](double x, double) { return std::tanh(50 * x); });
  SizeOptions o;
  o.complexity = 2 * 1024 * 9;
  SizeResult r = solve_feature_size(s, o);
  Mesh f = make_frame_mesh(s, r);
  const CellField* V = f.cell_field("Vinv");
  REQUIRE(V);
  CHECK(V->ncomp == 9);
  int front = 0;
  for (int k = 0; k < s.num_cells(); ++k) {
    if (std::abs(cell_centroid(s, k).x()) > 0.02) continue;
    ++front;
    Eigen::Matrix2d M;
    M << (*V)(k, 0), (*V)(k, 1), (*V)(k, 3), (*V)(k, 4);
    const Eigen::Matrix2d Vm = M.inverse();  // columns v, w
    const double ex = std::abs(Vm(0, 0)) + std::abs(Vm(0, 1)), ey = std::abs(Vm(1, 0)) + std::abs(Vm(1, 1));
    CHECK(ex < ey);
  }
  CHECK(front > 20);
  // front cells are smaller than far-field cells
  CHECK(*std::min_element(r.h.begin(), r.h.end()) < 0.2 * *std::max_element(r.h.begin(), r.h.end()));
}

TEST_CASE("goal-oriented fit (eqs. 5.22-5.25): meets C, respects r_max and c_max") {
  Mesh s = shape_of(make_perturbed_quads(16, 16, 0.2, 8), 2, sshock);
  std::mt19937 g(42);
  std::uniform_real_distribution<double> U(-9, 0);
  std::vector<double> eta(s.num_cells());
  for (double& e : eta) e = std::pow(10.0, U(g));
  eta[3] = 0;  // a zero indicator is floored, not a NaN
  GoalOptions go;
  for (double growth : {0.8, 1.0, 1.5, 3.0}) {
    CAPTURE(growth);
    SizeOptions o;
    o.complexity = growth * s.num_cells() * 9;
    SizeResult r = solve_goal_size(s, eta, o, go);
    CHECK(r.continuous_complexity == doctest::Approx(o.complexity).epsilon(1e-9));
    for (int k = 0; k < s.num_cells(); ++k) {
      CHECK(r.alpha[k] >= 1 / go.r_max * (1 - 1e-12));
      CHECK(r.alpha[k] <= go.c_max * (1 + 1e-12));
      CHECK(std::isfinite(r.h[k]));
      // target area 4 h^2 = α × current area (eq. 5.23)
      CHECK(4 * r.h[k] * r.h[k] == doctest::Approx(r.alpha[k] * std::abs(cell_area(s, k))).epsilon(1e-9));
      // α decreases with η: cells with larger indicators are refined more
      if (eta[k] > r.eta_ref) CHECK(r.alpha[k] <= 1 + 1e-12);
      if (eta[k] < r.eta_ref) CHECK(r.alpha[k] >= 1 - 1e-12);
    }
  }
  // out of reach: 30x the DOFs needs more than r_max = 20 everywhere
  SizeOptions o;
  o.complexity = 30.0 * s.num_cells() * 9;
  CHECK_THROWS_WITH_AS(solve_goal_size(s, eta, o, go, "dwr.msh"), doctest::Contains("outside the range"), InputError);
}

TEST_CASE("goal alpha: end values of the fit") {
  // η_max -> 1/r_max, η_min -> c_max, η_ref -> 1
  CHECK(goal_alpha(1.0, 1e-3, 1e-6, 1.0, 20, 4) == doctest::Approx(1.0 / 20));
  CHECK(goal_alpha(1e-6, 1e-3, 1e-6, 1.0, 20, 4) == doctest::Approx(4));
  CHECK(goal_alpha(1e-3, 1e-3, 1e-6, 1.0, 20, 4) == 1);
  // halfway in log space: ξ = 1/2 -> α = 1/((r-1)/4 + 1)
  CHECK(goal_alpha(std::sqrt(1e-3), 1e-3, 1e-6, 1.0, 20, 4) == doctest::Approx(1 / (19.0 / 4 + 1)));
}

TEST_CASE("DWR on another mesh: InputError") {
  Mesh a = make_structured_quads(4, 4), b = make_structured_quads(4, 5), c = make_perturbed_quads(4, 4, 0.2, 1);
  CHECK_NOTHROW(check_same_cells(a, a, "d.msh"));
  CHECK_THROWS_WITH_AS(check_same_cells(a, b, "d.msh"), doctest::Contains("another mesh"), InputError);
  CHECK_THROWS_WITH_AS(check_same_cells(a, c, "d.msh"), doctest::Contains("centroid"), InputError);
}
