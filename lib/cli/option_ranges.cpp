#include "cli/option_ranges.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <optional>
#include <regex>
#include <sys/stat.h>

#include "cli/parse_errors.hpp"

namespace quadapt {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

std::string num(double v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

std::string interval(const OptionRange& r) {
  return std::string(r.lo_open ? "(" : "[") + num(r.lo) + ", " + num(r.hi) + (r.hi_open || std::isinf(r.hi) ? ")" : "]");
}

bool parse_number(const std::string& s, double& v) {
  char* end = nullptr;
  v = std::strtod(s.c_str(), &end);
  return end != s.c_str() && *end == '\0';
}
}  // namespace

const std::vector<OptionRange>& option_ranges() {
  // clang-format off
  static const std::vector<OptionRange> table = {
      // tool            option                     lo     hi     lo_open hi_open
      {"*",              "--rtol",                  0,     1,     true,  true},
      {"*",              "--penalty",               0,     kInf,  true,  false},
      {"*",              "--max-iterations",        1,     kInf,  false, false},
      {"*",              "--norm-q",                1,     kInf,  false, false},
      {"*",              "--max-anisotropy",        1,     kInf,  false, false},
      {"*",              "--complexity",            0,     kInf,  true,  false},
      // size ratio between neighbours: 0 = off; BAMG ignores its -ratio below 1.1 (measured)
      {"*",              "--gradation",             1,     kInf,  true,  false, true},
      {"bamgquad",       "--gradation",             1.1,   kInf,  false, false, true},
      {"lpcvt",          "--scale",                 0,     kInf,  true,  false},
      {"lpcvt",          "--weight",                0,     kInf,  false, false},
      {"lpcvt",          "--initial",               0,     kInf,  false, false},
      {"lpcvt",          "--delta",                 0,     1,     false, true},
      {"lpcvt",          "--past",                  1,     kInf,  false, false},
      {"lpcvt",          "--move-tol",              0,     kInf,  false, false},
      {"lpcvt",          "--edge-tol",              0,     kInf,  false, false},
      {"lpcvt",          "--gtol",                  0,     kInf,  false, false},
      {"lpcvt",          "--lmin",                  0,     kInf,  false, false},
      {"lpcvt",          "--lmax",                  0,     kInf,  true,  false},
      {"lpcvt",          "--change-tol",            0,     1,     false, false},
      {"lpcvt",          "--ramp-after",            0,     kInf,  false, false},
      {"lpcvt",          "--lattice-phase",         0,     1,     false, true},
      {"quadsmooth",     "--frame-gradation",       1,     kInf,  true,  false, true},
      {"quadsmooth",     "--relaxation",            0,     2,     true,  true},
      {"size-solve",     "--growth",                0,     kInf,  true,  false},
      {"size-solve",     "--hmin",                  0,     kInf,  false, false},
      {"size-solve",     "--hmax",                  0,     kInf,  false, false},
      {"size-solve",     "--r-max",                 1,     kInf,  false, false},
      {"size-solve",     "--c-max",                 1,     kInf,  false, false},
      {"refine",         "--fraction",              0,     1,     true,  false},
      {"meshplot",       "--glyph-scale",           0,     kInf,  true,  false},
      {"meshplot",       "--width",                 16,    20000, false, false},
      {"meshplot",       "--subsample",             0,     64,    false, false},
  };
  // clang-format on
  return table;
}

CLI::Validator range_check(const OptionRange& r) {
  return CLI::Validator(
      [r](std::string& s) {
        double v;
        if (!parse_number(s, v)) return std::string();  // the type conversion reports it
        const bool ok = (r.lo_open ? v > r.lo : v >= r.lo) && (r.hi_open ? v < r.hi : v <= r.hi);
        if (ok || (r.zero_off && v == 0)) return std::string();
        return s + (r.zero_off ? " is not 0 (off) or in " : " is not in ") + interval(r);
      },
      // the range in --help ("--rtol FLOAT:(0, 1)"), the one that is enforced
      (r.zero_off ? "0 or " : "") + interval(r), std::string("range ") + r.option);
}

// Deactivates the first active validator of `opt` for which `replacement` gives one, and adds
// that one instead. No-op when none does.
void replace_validator(CLI::Option* opt,
                       const std::function<std::optional<CLI::Validator>(const CLI::Validator&)>& replacement) {
  for (int k = 0;; ++k) {
    CLI::Validator* v = nullptr;
    try {
      v = opt->get_validator(k);
    } catch (const CLI::OptionNotFound&) {
      return;
    }
    if (!v->get_active()) continue;
    std::optional<CLI::Validator> r = replacement(*v);
    if (!r) continue;
    v->active(false);
    opt->check(*r);
    return;
  }
}

// A CLI::Range's closed interval, read back from its description ("FLOAT in [0 - 0.45]",
// "INT in [1 - 6]"); false for any other validator.
bool cli11_range(const CLI::Validator& v, double& lo, double& hi) {
  static const std::regex re(R"(^[A-Z]+ in \[(\S+) - (\S+)\]$)");
  std::smatch m;
  const std::string d = v.get_description();
  return std::regex_match(d, m, re) && parse_number(m[1], lo) && parse_number(m[2], hi);
}

// CLI::ExistingFile also accepts "-" (standard input), and says "FILE: no such file" the way
// every other message names a file (cli/parse_errors: the runner prints it without the option
// name CLI11 puts first; it said "MESH: File does not exist: FILE"). A CLI::Range says its range
// like the table's ("--jitter: -1 is not in [0, 0.45]"; it said "Value -1 not in range 0.000000
// to 0.450000"). (Positive / non-negative checks are cli/parse_errors' PositiveValue /
// NonNegativeValue, which the tools attach themselves.)
void replace_cli11_checks(CLI::Option* opt, const std::string& name) {
  const CLI::Validator file(
      [](std::string& s) {
        if (s == "-") return std::string();
        if (s.empty()) return std::string("empty file name \"\"");
        struct stat st {};
        if (::stat(s.c_str(), &st) != 0) return file_problem(s, "no such file");
        if (S_ISDIR(st.st_mode)) return file_problem(s, "is a directory; give a file");
        return std::string();
      },
      "FILE|-", "input file");
  replace_validator(opt, [&](const CLI::Validator& v) -> std::optional<CLI::Validator> {
    if (v.get_description() != "FILE") return std::nullopt;
    return file;
  });
  replace_validator(opt, [](const CLI::Validator& v) -> std::optional<CLI::Validator> {
    double lo, hi;
    if (!cli11_range(v, lo, hi)) return std::nullopt;
    return range_check(OptionRange{"", "", lo, hi, false, false});
  });
}

void apply_option_ranges(const std::string& tool, CLI::App& app) {
  for (CLI::Option* opt : app.get_options()) {
    if (opt->get_type_size() == 0) continue;  // a flag
    const std::string name = opt->get_lnames().empty() ? "" : "--" + opt->get_lnames().front();
    replace_cli11_checks(opt, name);
    // "FLOAT", or "FLOAT:POSITIVE", "FLOAT:FLOAT in [2 - 32]" once a tool attached a check (whose
    // comparisons a NaN passes, and an overflowing 1e400 = inf passes a lower bound)
    if (opt->get_type_name().rfind("FLOAT", 0) == 0) {
      opt->check(CLI::Validator(
          [](std::string& s) {
            double v;
            if (parse_number(s, v) && !std::isfinite(v)) return s + " is not a finite number";
            return std::string();
          },
          "", "finite"));
    }
    // the tool's own row if it has one, else the "*" row
    const OptionRange* row = nullptr;
    for (const OptionRange& r : option_ranges()) {
      if (name != r.option) continue;
      if (r.tool == tool) row = &r;
      else if (std::string(r.tool) == "*" && !row) row = &r;
    }
    if (row) opt->check(range_check(*row));
  }
}

int clamp_threads(long requested) {
  const long limit = std::max(1, 4 * omp_get_num_procs());
  if (requested <= 0) requested = omp_get_max_threads();
  return int(std::clamp(requested, 1L, limit));
}

}  // namespace quadapt
