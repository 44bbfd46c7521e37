#include <doctest/doctest.h>

#include <cmath>
#include <functional>
#include <string>

#include "case/expression.hpp"
#include "core/error.hpp"

using namespace quadapt;

namespace {
double ev(const std::string& s, double x = 0.3, double y = -0.7) { return evaluate(parse_expression(s), x, y); }

std::string parse_error(const std::string& s) {
  try {
    parse_expression(s);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// 8th-order central finite difference of g around 0 — only an independent check of the
// symbolic derivatives, never the implementation.
double fd(const std::function<double(double)>& g, double h) {
  return (4.0 / 5 * (g(h) - g(-h)) - 1.0 / 5 * (g(2 * h) - g(-2 * h)) + 4.0 / 105 * (g(3 * h) - g(-3 * h)) -
          1.0 / 280 * (g(4 * h) - g(-4 * h))) /
         h;
}
}  // namespace

TEST_CASE("parser: numbers, precedence, associativity, constants") {
  CHECK(ev("1 + 2 * 3") == 7);
  CHECK(ev("(1 + 2) * 3") == 9);
  CHECK(ev("2 ^ 3 ^ 2") == 512);  // right-associative
  CHECK(ev("-2 ^ 2") == -4);      // unary minus binds weaker than ^
  CHECK(ev("2 ^ -1") == 0.5);
  CHECK(ev("8 / 4 / 2") == 1);    // left-associative
  CHECK(ev("10 - 4 - 3") == 3);
  CHECK(ev("--3") == 3);
  CHECK(ev("+3") == 3);
  CHECK(ev("1.5e2 + .5 + 2E-1") == doctest::Approx(150.7).epsilon(1e-15));
  CHECK(ev("pi") == M_PI);
  CHECK(ev("e") == M_E);
  CHECK(ev("2*e") == 2 * M_E);
  CHECK(ev("x*y", 2, 3) == 6);
  CHECK(ev("x - -y", 2, 3) == 5);
}

TEST_CASE("parser: every function matches the C library") {
  const double x = 0.37, y = 1.3;
  CHECK(ev("sin(x)", x, y) == std::sin(x));
  CHECK(ev("cos(x)", x, y) == std::cos(x));
  CHECK(ev("tan(x)", x, y) == std::tan(x));
  CHECK(ev("exp(x)", x, y) == std::exp(x));
  CHECK(ev("log(y)", x, y) == std::log(y));
  CHECK(ev("sqrt(y)", x, y) == std::sqrt(y));
  CHECK(ev("tanh(x)", x, y) == std::tanh(x));
  CHECK(ev("sinh(x)", x, y) == std::sinh(x));
  CHECK(ev("cosh(x)", x, y) == std::cosh(x));
  CHECK(ev("atan(x)", x, y) == std::atan(x));
  CHECK(ev("abs(x - y)", x, y) == std::abs(x - y));
  CHECK(ev("pow(y, x)", x, y) == std::pow(y, x));
  CHECK(ev("y ^ x", x, y) == std::pow(y, x));
}

TEST_CASE("parser: errors give the column and the offending token") {
  std::string m = parse_error("sin(x))");
  CHECK(m.find("column 7") != std::string::npos);
  CHECK(m.find("')'") != std::string::npos);
  m = parse_error("x + * y");
  CHECK(m.find("column 5") != std::string::npos);
  CHECK(m.find("'*'") != std::string::npos);
  m = parse_error("2 * z");
  CHECK(m.find("column 5") != std::string::npos);
  CHECK(m.find("'z'") != std::string::npos);
  CHECK(m.find("unknown name") != std::string::npos);
  m = parse_error("sin(x");
  CHECK(m.find("column 6") != std::string::npos);
  CHECK(m.find("at the end") != std::string::npos);
  m = parse_error("x $ y");
  CHECK(m.find("column 3") != std::string::npos);
  CHECK(m.find("'$'") != std::string::npos);
  CHECK(parse_error("").find("empty") != std::string::npos);
  CHECK(parse_error("2 x").find("column 3") != std::string::npos);
  CHECK(parse_error("pow(x)").find("','") != std::string::npos);
  CHECK(parse_error("sin x").find("'('") != std::string::npos);
  CHECK(parse_error("sin x").find("missing operator") == std::string::npos);
  // an implicit product inside parentheses: the hint, not only "expected ')'"
  m = parse_error("tanh(50(x + y - 1))");
  CHECK(m.find("column 8") != std::string::npos);
  CHECK(m.find("missing operator? write 50*(x + 1)") != std::string::npos);
  CHECK(parse_error("sin(2 x)").find("missing operator?") != std::string::npos);
  CHECK(parse_error("2e").find("'e'") != std::string::npos);  // "2e" is not a number
  CHECK_THROWS_AS(parse_constant("1 + x"), InputError);
  CHECK(parse_constant("0.01*pi/e*12") == doctest::Approx(0.01 * M_PI / M_E * 12).epsilon(1e-15));
}

TEST_CASE("symbolic derivatives against hand-derived values") {
  // u = 0.75 tanh(4 sin(10y-5) - 24x + 12): the S-shock (thesis eq. 6.4).
  Expr u = parse_expression("0.75*tanh(4*sin(10*y-5) - 24*x + 12)");
  for (auto [x, y] : {std::pair{0.5, 0.5}, std::pair{0.3, 0.8}, std::pair{0.61, 0.2}}) {
    double a = 4 * std::sin(10 * y - 5) - 24 * x + 12;
    double t = std::tanh(a), sech2 = 1 - t * t;
    double ax = -24, ay = 40 * std::cos(10 * y - 5), ayy = -400 * std::sin(10 * y - 5);
    // d/da tanh = sech^2, d2/da2 tanh = -2 tanh sech^2
    double ux = 0.75 * sech2 * ax, uy = 0.75 * sech2 * ay;
    double uxx = 0.75 * (-2 * t * sech2) * ax * ax;
    double uxy = 0.75 * (-2 * t * sech2) * ax * ay;
    double uyy = 0.75 * ((-2 * t * sech2) * ay * ay + sech2 * ayy);
    Expr dx = differentiate(u, 0), dy = differentiate(u, 1);
    CHECK(evaluate(dx, x, y) == doctest::Approx(ux).epsilon(1e-13));
    CHECK(evaluate(dy, x, y) == doctest::Approx(uy).epsilon(1e-13));
    CHECK(evaluate(differentiate(dx, 0), x, y) == doctest::Approx(uxx).epsilon(1e-12));
    CHECK(evaluate(differentiate(dx, 1), x, y) == doctest::Approx(uxy).epsilon(1e-12));
    CHECK(evaluate(differentiate(dy, 0), x, y) == doctest::Approx(uxy).epsilon(1e-12));
    CHECK(evaluate(differentiate(dy, 1), x, y) == doctest::Approx(uyy).epsilon(1e-12));
  }
  // Boundary layer (eq. 6.5), one factor: f = x + (exp(x/eps) - 1)/(1 - exp(1/eps)).
  {
    const double eps = 0.05;
    Expr f = parse_expression("x + (exp(x/0.05) - 1)/(1 - exp(1/0.05))");
    double x = 0.9, E = 1 - std::exp(1 / eps);
    CHECK(evaluate(differentiate(f, 0), x, 0) == doctest::Approx(1 + std::exp(x / eps) / eps / E).epsilon(1e-13));
    CHECK(evaluate(differentiate(differentiate(f, 0), 0), x, 0) ==
          doctest::Approx(std::exp(x / eps) / (eps * eps) / E).epsilon(1e-13));
    CHECK(evaluate(differentiate(f, 1), x, 0) == 0);
  }
  // Powers and quotients: d/dx x^y = y x^(y-1), d/dy x^y = x^y log x; d/dx 1/x = -1/x^2.
  CHECK(evaluate(differentiate(parse_expression("x^y"), 0), 2, 3) == doctest::Approx(12));
  CHECK(evaluate(differentiate(parse_expression("x^y"), 1), 2, 3) == doctest::Approx(8 * std::log(2.0)));
  CHECK(evaluate(differentiate(parse_expression("1/x"), 0), 2, 3) == doctest::Approx(-0.25));
  CHECK(evaluate(differentiate(parse_expression("2^x"), 0), 3, 0) == doctest::Approx(8 * std::log(2.0)));
  CHECK(evaluate(differentiate(parse_expression("sqrt(x)"), 0), 4, 0) == doctest::Approx(0.25));
  CHECK(evaluate(differentiate(parse_expression("abs(x)"), 0), -2, 0) == -1);
  CHECK(evaluate(differentiate(parse_expression("atan(2*x)"), 0), 0.5, 0) == doctest::Approx(1.0));
  CHECK(evaluate(differentiate(parse_expression("log(x*y)"), 1), 2, 4) == doctest::Approx(0.25));
  CHECK(evaluate(differentiate(parse_expression("tan(x)"), 0), 0.3, 0) ==
        doctest::Approx(1 / (std::cos(0.3) * std::cos(0.3))));
  // Simplification: constants fold and trivial identities vanish.
  CHECK(to_string(differentiate(parse_expression("3*x + 2"), 0)) == "3");
  CHECK(to_string(differentiate(parse_expression("x^2"), 1)) == "0");
}

TEST_CASE("symbolic derivatives of composite expressions agree with 8th-order finite differences") {
  const char* exprs[] = {
      "sin(pi*x)*cos(2*y) + exp(x*y)/(1 + x^2)",
      "pow(1 + x^2 + y^2, 1.5) - sqrt(2 + sin(x*y))",
      "atan(3*x - y) * tanh(x + 2*y) + log(2 + cosh(x) * sinh(y))",
      "(x + y)^3 / (2 + tan(0.3*x)) - abs(x - 2) + e^(x - y)",
      "x ^ (1 + y^2)",
  };
  const double h = 1e-3;
  for (const char* s : exprs) {
    CAPTURE(s);
    Expr u = parse_expression(s);
    for (auto [x, y] : {std::pair{0.4, 0.7}, std::pair{1.1, -0.35}}) {
      for (int ax = 0; ax < 2; ++ax) {
        Expr d = differentiate(u, ax);
        auto g = [&](const Expr& f, int axis) {
          return [=](double t) { return evaluate(f, x + (axis == 0 ? t : 0), y + (axis == 1 ? t : 0)); };
        };
        CHECK(evaluate(d, x, y) == doctest::Approx(fd(g(u, ax), h)).epsilon(1e-9));
        for (int ax2 = 0; ax2 < 2; ++ax2) {
          Expr d2 = differentiate(d, ax2);
          CHECK(evaluate(d2, x, y) == doctest::Approx(fd(g(d, ax2), h)).epsilon(1e-8));
        }
      }
    }
  }
}

TEST_CASE("compiled program: same values as the tree, shared sub-expressions counted once") {
  Expr u = parse_expression("0.75*tanh(4*sin(10*y-5) - 24*x + 12) + x^2*y^-3");
  Expr ux = differentiate(u, 0), uy = differentiate(u, 1);
  Expr uxx = differentiate(ux, 0), uyy = differentiate(uy, 1);
  ExprProgram prog({u, ux, uy, uxx, uyy});
  for (auto [x, y] : {std::pair{0.2, 0.9}, std::pair{0.55, 0.45}}) {
    std::vector<double> v = prog.eval(x, y);
    CHECK(v[0] == doctest::Approx(evaluate(u, x, y)).epsilon(1e-15));
    CHECK(v[1] == doctest::Approx(evaluate(ux, x, y)).epsilon(1e-14));
    CHECK(v[2] == doctest::Approx(evaluate(uy, x, y)).epsilon(1e-14));
    CHECK(v[3] == doctest::Approx(evaluate(uxx, x, y)).epsilon(1e-14));
    CHECK(v[4] == doctest::Approx(evaluate(uyy, x, y)).epsilon(1e-14));
  }
  // tanh(...) appears in every output but is computed once.
  CHECK(prog.num_slots() < expr_size(u) + expr_size(ux) + expr_size(uy) + expr_size(uxx) + expr_size(uyy));
  // ... by its structure, not only as one shared node: two separate parses of the same text add
  // no slot (the bound above holds with node sharing alone: a test audit, session 38)
  const char* text = "0.75*tanh(4*sin(10*y-5) - 24*x + 12) + x^2*y^-3";
  ExprProgram one({parse_expression(text)}), two({parse_expression(text), parse_expression(text)});
  CHECK(two.num_slots() == one.num_slots());
}
