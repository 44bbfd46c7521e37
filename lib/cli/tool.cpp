#include "cli/tool.hpp"

#include <omp.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "cli/help_examples.hpp"
#include "cli/parse_errors.hpp"
#include "cli/provenance.hpp"
#include "core/atomic_file.hpp"

namespace quadapt {

namespace {
constexpr const char* kExitCodes =
    "Exit codes: 0 success; 1 failure but a valid output was saved; 2 bad input or failure, "
    "nothing written; 3 internal error.";
}

Tool::Tool(std::string name, std::string summary, std::string details)
    : name_(std::move(name)), app_(summary, name_) {
  std::string footer = details.empty() ? std::string(kExitCodes) : details + "\n\n" + kExitCodes;
  const std::string example = help_example(name_);
  if (!example.empty()) footer += "\n\n" + example;
  app_.footer(footer);
  app_.set_version_flag("--version", version_text(name_));
  app_.add_option("--report", report_path_,
                  "JSON report path (default: the output path with extension .json)");
  app_.add_flag("-q,--quiet", quiet_, "No progress messages on stderr");
  app_.add_option("--threads", threads_,
                  "OpenMP threads (default: OMP_NUM_THREADS, else all cores)")
      ->check(NonNegativeValue);
  report_ = nlohmann::json::object();
}

void Tool::input(const std::string& path) {
  inputs_.push_back(path);
  report_["inputs"].push_back(path);
}

void Tool::output(const std::string& path) {
  check_not_an_input(path, inputs_);
  const auto key = [](const std::string& p) { return std::filesystem::absolute(p).lexically_normal(); };
  for (const std::string& o : outputs_)
    if (key(o) == key(path)) throw InputError(path, "given for two outputs; choose another path");
  if (!report_path_.empty() && key(report_path_) == key(path))
    throw InputError(path, "output would overwrite the report " + report_path_ + "; choose another path");
  outputs_.push_back(path);
  report_["outputs"].push_back(path);
  if (report_path_.empty()) {
    std::filesystem::path p(path);
    report_path_ = p.replace_extension(".json").string();
  }
  check_not_an_input(report_path_, inputs_);
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
  if (report_path_ == "-") {
    std::cout << report_.dump(2) << std::endl;
    return;
  }
  if (report_path_.empty()) return;
  atomic_write(report_path_, [&](std::ostream& os) { os << report_.dump(2) << "\n"; });
}

int Tool::run(int argc, char** argv, const std::function<void()>& body) {
  start_ = std::chrono::steady_clock::now();
  start_date_ = utc_now_iso8601();
  std::ostringstream cmd;
  for (int i = 0; i < argc; ++i) cmd << (i ? " " : "") << argv[i];
  report_["command"] = cmd.str();
  try {
    app_.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help, --version
    return app_.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << name_ << ": " << parse_error_message(app_, argc, argv, e) << " (see " << name_ << " --help)"
              << std::endl;
    return 2;
  }
  if (threads_ > 0) omp_set_num_threads(threads_);
  // Record every option's effective value (defaults included) as provenance.
  for (const CLI::Option* opt : app_.get_options()) {
    if (opt->get_name() == "--help" || opt->get_name() == "--version") continue;
    std::string key = opt->get_single_name();
    auto res = opt->results();
    if (res.empty()) {
      std::string def = opt->get_default_str();
      if (!def.empty()) report_["options"][key] = def;
    } else if (res.size() == 1) {
      report_["options"][key] = res[0];
    } else {
      report_["options"][key] = res;
    }
  }
  try {
    body();
    write_report();
    return 0;
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
