// libFuzzer target: the case-expression parser (case/expression) on arbitrary text; what parses
// is differentiated in x and y, printed, re-parsed, compiled and evaluated. Every rejection must
// be a quadapt::Error; any other exception, a crash or undefined behaviour is a bug.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <string>

#include "case/expression.hpp"
#include "core/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > 4096) return 0;  // case files hold short formulas; keeps each run fast
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    quadapt::Expr e = quadapt::parse_expression(text);
    if (quadapt::expr_size(e) > 2000) return 0;  // derivatives grow; bound the work per input
    quadapt::Expr dx = quadapt::differentiate(e, 0);
    quadapt::Expr dy = quadapt::differentiate(e, 1);
    (void)quadapt::evaluate(e, 0.3, -0.7);
    (void)quadapt::evaluate(dx, 0.3, -0.7);
    (void)quadapt::evaluate(dy, 0.3, -0.7);
    (void)quadapt::depends_on_xy(e);
    (void)quadapt::ExprProgram({e, dx, dy}).eval(0.3, -0.7);
    quadapt::Expr back = quadapt::parse_expression(quadapt::to_string(e));
    (void)quadapt::evaluate(back, 0.3, -0.7);
  } catch (const quadapt::Error&) {
    // a clean rejection
  } catch (const std::exception& e) {
    std::cerr << "non-quadapt exception (exit 3 in a tool): " << e.what() << std::endl;
    std::abort();
  }
  return 0;
}
