#include "cli/tool.hpp"

#include <omp.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <cstdlib>
#include <iostream>
#include <sstream>

#include "cli/help_examples.hpp"
#include "cli/parse_errors.hpp"
#include "cli/provenance.hpp"
#include "cli/option_ranges.hpp"
#include "core/atomic_file.hpp"
#include "core/file_name.hpp"
#include "core/path_guard.hpp"
#include "core/signal_cleanup.hpp"
#include "io/msh.hpp"
#include "mesh/near_boundary.hpp"

namespace quadapt {

namespace {
constexpr const char* kExitCodes =
    "Exit codes: 0 success; 1 failure but a valid output was saved; 2 bad input or failure, "
    "nothing written; 3 internal error.";

// "--min-quality" -> "min_quality"; positionals keep their name ("MESH").
std::string option_key(const CLI::Option& opt) {
  std::string key = opt.get_single_name();
  for (char& c : key)
    if (c == '-') c = '_';
  return key;
}

// The command-line text of an option as JSON: numbers for FLOAT / INT options, booleans for
// flags, strings otherwise; an array when the option takes several values.
nlohmann::json typed_option_value(const CLI::Option& opt, const std::vector<std::string>& texts) {
  const std::string type = opt.get_type_name();
  const bool real = type.rfind("FLOAT", 0) == 0, integer = type.rfind("INT", 0) == 0 || type.rfind("UINT", 0) == 0;
  auto one = [&](const std::string& t) -> nlohmann::json {
    char* end = nullptr;
    if (real) {
      const double v = std::strtod(t.c_str(), &end);
      if (end != t.c_str() && *end == '\0') return v;
    } else if (integer) {
      const long long v = std::strtoll(t.c_str(), &end, 10);
      if (end != t.c_str() && *end == '\0') return v;
    } else if (opt.get_type_size() == 0 || opt.get_expected_min() == 0) {  // a flag (CLI11 sets either)
      if (t == "true" || t == "1" || t.empty()) return true;
      if (t == "false" || t == "0") return false;
    }
    return t;
  };
  if (texts.size() == 1) return one(texts[0]);
  nlohmann::json a = nlohmann::json::array();
  for (const std::string& t : texts) a.push_back(one(t));
  return a;
}

}  // namespace

/// Whether the file at path is a quadapt report: a JSON object with a "tool" string.
static bool is_tool_report(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  return j.is_object() && j.contains("tool") && j["tool"].is_string();
}

std::string default_report_path(const std::string& output) {
  const std::filesystem::path p(output);
  if (lower_extension(output) == ".msh") return std::filesystem::path(p).replace_extension(".json").string();
  return output + ".json";
}

Tool::Tool(std::string name, std::string summary, std::string details)
    : name_(std::move(name)), app_(summary, name_) {
  std::string footer = details.empty() ? std::string(kExitCodes) : details + "\n\n" + kExitCodes;
  const std::string example = help_example(name_);
  if (!example.empty()) footer += "\n\n" + example;
  app_.footer(footer);
  app_.set_version_flag("--version", version_text(name_));
  app_.add_option("--report", report_path_,
                  "JSON report path (default: beside the output, OUT.msh -> OUT.json; any other output name "
                  "gets .json appended, e.g. meshconvert's sol.vtu -> sol.vtu.json, never over sol.json)");
  app_.add_flag("-q,--quiet", quiet_, "No progress messages on stderr");
  app_.add_option("--threads", threads_,
                  "OpenMP threads (default: OMP_NUM_THREADS, else all cores; at most 4 x the cores)")
      ->check(NonNegativeValue);
  report_ = nlohmann::json::object();
}

void Tool::use_stdio(const std::string& path, bool& used, const char* what) {
  if (path != "-") return;
  if (used) throw InputError("-", std::string("standard ") + what + " is used twice; give a file name");
  used = true;
}

void Tool::input(const std::string& path) {
  use_stdio(path, stdin_used_, "input");
  protect_input(path);
  inputs_.push_back(path);
  report_["inputs"].push_back(path);
}

void Tool::output(const std::string& path) {
  // "", a directory, a missing folder: exit 2 before anything is written.
  const OutputTarget target = resolve_output(path);
  use_stdio(path, stdout_used_, "output");
  protect_output(path);
  // a mesh output may get its Gmsh options file beside it (io/gmsh_options.hpp; MSH is what a
  // .msh name or a name without extension gets): refused before any work when that is an input,
  // like the output itself
  const std::string ext = lower_extension(path);
  if (target.kind == OutputTarget::Kind::Regular && (ext == ".msh" || ext.empty())) {
    protect_output(path + ".opt", "the Gmsh options file written beside " + path);
    resolve_output(path + ".opt");  // a directory, a link into a missing folder: refused now, not after the work
  }
  outputs_.push_back(path);
  report_["outputs"].push_back(path);
  if (!report_decided_) {
    report_decided_ = true;
    // Beside the first output; none when that is standard output, a device or a FIFO (unless
    // --report): /dev/stdout.json is nobody's report.
    report_explicit_ = !report_path_.empty();
    if (report_path_.empty() && target.kind == OutputTarget::Kind::Regular) report_path_ = default_report_path(path);
    declare_report();
  }
}

void Tool::output_mesh(const std::string& path) {
  output(path);  // its refusals first (an input, a missing folder, ...): they name the worse mistake
  const std::filesystem::path p(path);
  const std::string ext = lower_extension(path);
  if (path != "-" && !ext.empty() && ext != ".msh") {
    const std::string stem = (p.parent_path() / p.stem()).string();
    throw InputError(path, name_ + " writes Gmsh MSH only: name the output " + stem +
                               ".msh (for ParaView or another format: meshconvert " + stem + ".msh -o " + path + ")");
  }
}

void Tool::set_report_path(const std::string& p) {
  report_path_ = p;
  report_decided_ = true;
  report_explicit_ = true;
  declare_report();
}

void Tool::output_json(const std::string& path, const std::string& what) {
  output(path);
  if (path != "-") refuse_foreign_json(path, what, /*report=*/false, "give " + what + " another path", /*allow_empty=*/true);
}

void Tool::refuse_foreign_json(const std::string& path, const std::string& what, bool report, const std::string& fix,
                               bool allow_empty) {
  // a JSON output named like a file the toolkit reads or writes (`--report keep.msh`, a picture,
  // the loop's table, Gmsh's options) would overwrite it with JSON
  const std::string ext = lower_extension(path);
  static const char* const kNotJson[] = {".msh", ".vtu", ".vtk", ".geo", ".png", ".svg", ".pdf", ".csv", ".opt"};
  if (std::find(std::begin(kNotJson), std::end(kNotJson), ext) != std::end(kNotJson))
    throw InputError(path, what + " writes " + (report ? "a JSON report" : "JSON") + ", not " +
                               (std::string("aeiou").find(ext[1]) != std::string::npos ? "an " : "a ") + ext.substr(1) +
                               " file: give it a .json name");
  // nor a file of the user's that is in the way (`--report case.json` of a case not read this
  // time, `-o mm1.msh` beside a case file mm1.json): only a quadapt JSON (an earlier report, an
  // earlier --voronoi) is replaced, and an empty file where allowed
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec || (allow_empty && size == 0) || is_tool_report(path)) return;
  throw InputError(path, std::string("exists and is not ") + (report ? "a quadapt report" : "quadapt's JSON (no \"tool\" key)") +
                             "; " + what + " would replace it: " + fix);
}

void Tool::declare_report() {
  if (report_path_.empty()) return;
  resolve_output(report_path_);
  use_stdio(report_path_, stdout_used_, "output");
  // named in a refusal: `dgsolve M -c X.json -o X.msh` would write its report X.json over the case
  if (report_explicit_) {
    protect_output(report_path_, "the report (--report)", "give --report another path");
    if (report_path_ != "-")
      refuse_foreign_json(report_path_, "--report", /*report=*/true, "give --report another path (or remove the file)",
                          /*allow_empty=*/true);
  } else {
    const std::string beside = "the report written beside the output " + (outputs_.empty() ? std::string() : outputs_.front());
    protect_output(report_path_, beside, "give --report another path, or -o another name");
    refuse_foreign_json(report_path_, beside, /*report=*/true, "give --report another path, or -o another name",
                        /*allow_empty=*/false);
  }
}

Mesh Tool::read_mesh(const std::string& path, const ValidateOptions& v) {
  Mesh m = read_valid_msh(path, v);
  for (const std::string& w : boundary_warnings(m)) warn(path + ": " + w);
  return m;
}

void Tool::warn(const std::string& msg) {
  log("warning: " + msg);
  report_["warnings"].push_back(msg);
}

void Tool::log(const std::string& msg) const {
  if (!quiet_) std::cerr << name_ << ": " << msg << std::endl;
}

Tool::Phase::Phase(Tool& t, std::string name)
    : tool_(t), name_(std::move(name)), start_(std::chrono::steady_clock::now()) {}

Tool::Phase::~Phase() {
  double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  auto& slot = tool_.report_["timings"][name_];
  slot = (slot.is_number() ? slot.get<double>() : 0.0) + s;
}

void Tool::write_report() {
  report_["tool"] = name_;
  report_["version"] = QUADAPT_VERSION;
  report_["threads"] = omp_get_max_threads();
  report_["peak_memory_mb"] = peak_memory_mb();
  nlohmann::json prov = build_provenance();
  prov["date"] = start_date_;
  prov["host"] = host_provenance();
  prov["input_sha256"] = input_checksums(inputs_);
  report_["provenance"] = prov;
  report_["timings"]["total"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (report_path_.empty()) return;
  atomic_write(report_path_, [&](std::ostream& os) { os << report_.dump(2) << "\n"; });
}

int Tool::run(int argc, char** argv, const std::function<void()>& body) {
  start_ = std::chrono::steady_clock::now();
  start_date_ = utc_now_iso8601();
  // an interrupt removes the temporaries and child processes the library registered
  install_signal_cleanup();
  std::ostringstream cmd;
  for (int i = 0; i < argc; ++i) cmd << (i ? " " : "") << argv[i];
  report_["command"] = cmd.str();
  apply_option_ranges(name_, app_);
  try {
    app_.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help, --version
    return app_.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << name_ << ": " << parse_error_message(app_, argc, argv, e)
              << (is_file_problem(e) ? "" : " (see " + name_ + " --help)") << std::endl;
    return 2;
  }
  // An option given as "" (`--report ""`, `--voronoi ""`) is refused, not taken for "not given"
  // (it wrote the default report, or nothing at all, with exit 0).
  // Options whose "" means something (meshplot's `--title ''`: no title) are declared with
  // allow_empty_value.
  for (const CLI::Option* opt : app_.get_options()) {
    if (opt->get_type_size() == 0 || opt->count() == 0) continue;
    if (std::find(may_be_empty_.begin(), may_be_empty_.end(), opt->get_name()) != may_be_empty_.end()) continue;
    for (const std::string& r : opt->results())
      if (r.empty()) {
        std::cerr << name_ << ": " << opt->get_name() << ": empty value \"\" (give a file name or value)" << std::endl;
        return 2;
      }
  }
  const int threads = clamp_threads(threads_);
  if (threads_ > threads) log("--threads " + std::to_string(threads_) + " is more than this machine runs; using " + std::to_string(threads));
  omp_set_num_threads(threads);
  // Record every option's value (defaults included) as provenance, typed and under the key the
  // tools use for the effective values they record (tool.option("min_quality", 0.3) replaces
  // "--min-quality 0.3"): one entry per option. It was the CLI11 text under the option's own
  // spelling beside the tool's typed one ('min-quality': '0' and 'min_quality': 0.0).
  for (const CLI::Option* opt : app_.get_options()) {
    if (opt->get_name() == "--help" || opt->get_name() == "--version") continue;
    auto res = opt->results();
    if (res.empty()) {
      const std::string def = opt->get_default_str();
      const bool flag = opt->get_type_size() == 0 || opt->get_expected_min() == 0;
      if (def.empty() && !flag) continue;  // an option without a default, not given: absent
      res = {def.empty() ? std::string("false") : def};  // a flag not given: false
    }
    report_["options"][option_key(*opt)] = typed_option_value(*opt, res);
  }
  report_["options"]["threads"] = threads;  // the effective count
  clear_protected_paths();  // one run per process; tests run several
  enable_input_guard();
  struct GuardOff {
    ~GuardOff() { enable_input_guard(false); }
  } guard_off;
  try {
    body();
  } catch (const PartialFailure& e) {
    std::cerr << name_ << ": " << e.what() << std::endl;
    try { write_report(); } catch (...) {}
    return 1;
  } catch (const Error& e) {
    std::cerr << name_ << ": " << e.what() << std::endl;
    return 2;
  } catch (const std::string& s) {  // Gmsh 4.8 throws std::string
    std::cerr << name_ << ": Gmsh error: " << s << std::endl;
    return 2;
  } catch (const std::exception& e) {
    std::cerr << name_ << ": internal error: " << e.what() << std::endl;
    return 3;
  } catch (...) {
    std::cerr << name_ << ": internal error (unknown exception)" << std::endl;
    return 3;
  }
  // The outputs are written and valid; a report that cannot be written (a full disk) is a
  // failure with a valid output saved: exit 1 (2 where the report is the only output).
  try {
    write_report();
    return 0;
  } catch (const Error& e) {
    std::cerr << name_ << ": " << e.what() << (outputs_.empty() ? "" : " (the outputs were written)") << std::endl;
    return outputs_.empty() ? 2 : 1;
  } catch (const std::exception& e) {
    std::cerr << name_ << ": internal error: " << e.what() << std::endl;
    return 3;
  }
}

double peak_memory_mb() {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("VmHWM:", 0) == 0) {
      std::istringstream ss(line.substr(6));
      double kb = 0;
      ss >> kb;
      return kb / 1024.0;
    }
  }
  return 0.0;
}

}  // namespace quadapt
