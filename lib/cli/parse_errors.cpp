#include "cli/parse_errors.hpp"

#include <cctype>
#include <cstdlib>
#include <regex>
#include <sstream>
#include <vector>

#include "core/format.hpp"

namespace quadapt {

namespace {
// Starts a file_problem inside CLI11's "NAME: message" (a control character no path or value has).
constexpr char kFileProblem = '\x1f';

bool is_number(const std::string& s) {
  if (s.empty()) return false;
  char* end = nullptr;
  std::strtod(s.c_str(), &end);
  return end && *end == '\0';
}

CLI::Validator bound_validator(bool strict, const char* name) {
  return CLI::Validator(
      [strict](std::string& in) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(in.c_str(), &end);
        if (in.empty() || !end || *end != '\0') return "value '" + in + "' is not a number";
        if (strict ? !(v > 0) : !(v >= 0)) return std::string("must be ") + (strict ? "> 0" : ">= 0") + " (got " + in + ")";
        return "";
      },
      name);
}
}  // namespace

std::string file_problem(const std::string& file, const std::string& problem) {
  return std::string(1, kFileProblem) + file + ": " + problem;
}

bool is_file_problem(const CLI::ParseError& e) { return std::string(e.what()).find(kFileProblem) != std::string::npos; }

const CLI::Validator PositiveValue = bound_validator(true, "POSITIVE");
const CLI::Validator NonNegativeValue = bound_validator(false, "NONNEGATIVE");

std::string first_unknown_option(const CLI::App& app, int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "--") break;  // everything after is positional
    // "-", negative numbers and values such as "-6,4" (meshplot --range) are not options
    if (a.size() < 2 || a[0] != '-' || is_number(a) || std::isdigit(static_cast<unsigned char>(a[1])) || a[1] == '.')
      continue;
    std::string name = a.substr(0, a.find('='));
    if (name.size() > 2 && name[1] != '-') name = name.substr(0, 2);  // -p2 -> -p
    if (app.get_option_no_throw(name) == nullptr) return a.substr(0, a.find('='));
  }
  return "";
}

std::string parse_error_message(const CLI::App& app, int argc, char** argv, const CLI::ParseError& e) {
  const std::string unknown = first_unknown_option(app, argc, argv);
  if (!unknown.empty()) return "unknown option " + unknown;
  std::string msg = e.what();
  if (const size_t f = msg.find(kFileProblem); f != std::string::npos) return msg.substr(f + 1);
  // CLI11's "Could not convert: --degree = 2.5": say what the option takes
  static const std::regex convert(R"(Could not convert: (\S+) = (.*))");
  if (std::smatch m; std::regex_search(msg, m, convert)) {
    const CLI::Option* o = app.get_option_no_throw(m[1].str());
    const std::string type = o ? o->get_type_name() : "";
    const char* what = type.rfind("INT", 0) == 0    ? "a whole number"
                       : type.rfind("UINT", 0) == 0 ? "a non-negative whole number"
                       : type.rfind("FLOAT", 0) == 0 ? "a number"
                                                     : nullptr;
    // a whole number too large for the option's type is not "not a whole number"
    static const std::regex integer(R"(\s*[-+]?[0-9]+\s*)");
    if (what && type.rfind("FLOAT", 0) != 0 && std::regex_match(m[2].str(), integer))
      return m[1].str() + " " + m[2].str() + ": a whole number out of range";
    if (what) return m[1].str() + " " + m[2].str() + ": not " + what;
  }
  // CLI11's count messages, in the tools' words
  static const std::regex at_least(R"((\S+): At least (\d+) required but received (\d+))");
  if (std::smatch m; std::regex_search(msg, m, at_least))
    return m[1].str() + " takes " + m[2].str() + " values, got " + m[3].str();
  static const std::regex at_most(R"((\S+): At Most 1 required but received (\d+))");
  if (std::smatch m; std::regex_search(msg, m, at_most))
    return m[1].str() + " is given " + m[2].str() + " times: give it once";
  static const std::regex extras(R"(The following arguments? (?:was|were) not expected: (.*))");
  if (std::smatch m; std::regex_search(msg, m, extras)) {
    // CLI11 lists them last first
    std::vector<std::string> args;
    std::istringstream is(m[1].str());
    for (std::string a; is >> a;) args.insert(args.begin(), a);
    std::string list;
    for (const std::string& a : args) list += (list.empty() ? "" : " ") + a;
    return "unexpected argument" + std::string(args.size() > 1 ? "s " : " ") + list;
  }
  static const std::regex long_number(R"(-?[0-9]+\.?[0-9]*(?:[eE][-+]?[0-9]+)?)");
  std::string out;
  auto it = std::sregex_iterator(msg.begin(), msg.end(), long_number);
  size_t last = 0;
  for (; it != std::sregex_iterator(); ++it) {
    const auto& m = *it;
    out += msg.substr(last, m.position() - last);
    out += m.length() > 12 ? sci(std::strtod(m.str().c_str(), nullptr)) : m.str();
    last = m.position() + m.length();
  }
  return out + msg.substr(last);
}

}  // namespace quadapt
