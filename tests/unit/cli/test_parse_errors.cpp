// lib/cli/parse_errors: unknown options named, long numbers shortened, short validators.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "cli/parse_errors.hpp"

using namespace quadapt;

namespace {
std::string unknown(CLI::App& app, std::vector<std::string> args) {
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  return first_unknown_option(app, static_cast<int>(argv.size()), argv.data());
}
}  // namespace

TEST_CASE("first_unknown_option: names the option, not values, numbers or '-'") {
  CLI::App app("t", "tool");
  std::string in, out;
  double r = 0;
  int p = 0;
  app.add_option("IN", in)->required();
  app.add_option("-o,--output", out);
  app.add_option("-p,--degree", p);
  app.add_option("--range", r);
  CHECK(unknown(app, {"tool", "--bogus"}) == "--bogus");
  CHECK(unknown(app, {"tool", "x", "-o", "y", "--bogus=3"}) == "--bogus");
  CHECK(unknown(app, {"tool", "x", "-p2", "-o", "-"}) == "");
  CHECK(unknown(app, {"tool", "x", "--range", "-6,4", "--degree=-1", "-1e-3"}) == "");
  CHECK(unknown(app, {"tool", "x", "-z"}) == "-z");
  CHECK(unknown(app, {"tool", "--", "--bogus"}) == "");
}

TEST_CASE("validators: short messages with the bound") {
  std::string v = "-1";
  CHECK(NonNegativeValue(v) == "must be >= 0 (got -1)");
  v = "0";
  CHECK(NonNegativeValue(v) == "");
  CHECK(PositiveValue(v) == "must be > 0 (got 0)");
  v = "abc";
  CHECK(PositiveValue(v) == "value 'abc' is not a number");
}

TEST_CASE("parse_error_message: numbers longer than 12 characters in %.3e") {
  CLI::App app("t", "tool");
  const CLI::ValidationError e("--threads", "Value -1 not in range 0.000000 to 179769313486231570814527423731704356798070567525844996598917476803157260780028538760589558632766878171540458953514382464234321326889464182768467546703537516986049910576551282076245490090389328944075868508455133942304583236903222948165808559332123348274797826204144723168738177180919299881250404026184124858368.000000");
  std::string a0 = "tool";
  char* argv[] = {a0.data()};
  const std::string m = parse_error_message(app, 1, argv, e);
  CHECK(m.find("1.798e+308") != std::string::npos);
  CHECK(m.find("0.000000") != std::string::npos);  // short numbers are kept as they are
  CHECK(m.size() < 120);
}
