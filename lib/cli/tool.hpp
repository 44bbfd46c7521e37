#pragma once
// The one runner shared by every quadapt command-line tool (tools/*.cpp).
//
// A tool is an options struct plus one library call. tools/NAME.cpp only
//   1. builds a Tool, maps CLI11 flags onto its options struct,
//   2. calls Tool::run with a body that reads inputs, calls lib/, writes outputs.
// The runner supplies --help, --version, --report FILE, -q/--quiet, --threads N, catches every
// exception and turns it into ONE line on stderr plus the exit code below, and writes the JSON
// report (provenance: tool, version, command line, effective options, inputs, outputs,
// timings per phase, threads, peak memory, and under "provenance" the git commit, build type,
// library versions, date, host CPU and input sha256s: cli/provenance.hpp).
//
// Exit-code contract (docs/exit-codes.md):
//   0  success
//   1  failure, but a valid output was saved (body threw PartialFailure after writing)
//   2  failure, nothing written: bad input or options (InputError, CLI parse error), or a
//      numerical / external failure (NumericalError, ExternalError)
//   3  internal error (a bug: any other exception)
// SIGINT / SIGTERM / SIGHUP: the temporaries and child processes the library registered are
// removed (core/signal_cleanup.hpp) and the tool ends by the signal (a shell's 130 / 143).
#include <CLI/CLI.hpp>
#include <chrono>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "mesh/mesh.hpp"
#include "mesh/validate.hpp"

namespace quadapt {

/// Thrown by a tool body after it has written a valid (but e.g. unconverged) output: exit 1.
struct PartialFailure : Error {
  using Error::Error;
};

class Tool {
 public:
  /// `name` is the executable name; `summary` one line; `details` (optional) a paragraph for
  /// --help explaining method, inputs, outputs and equations.
  Tool(std::string name, std::string summary, std::string details = "");

  /// The CLI11 app: add the tool's own options here before run().
  CLI::App& app() { return app_; }

  /// Parses argv and runs body. Returns the exit code (use: return tool.run(argc, argv, ...)).
  int run(int argc, char** argv, const std::function<void()>& body);

  /// Declares an input file ("-": standard input), recorded in the report. No output may be
  /// the same file (core/path_guard: through symlinks, hard links and ..), whichever of the two
  /// is declared first; files read through read_msh / read_text_file are protected as well.
  void input(const std::string& path);
  /// Declares an output file ("-": standard output; see core/atomic_file for symlinks, devices
  /// and FIFOs). Throws InputError (exit 2, nothing written) for "", a directory, a missing
  /// folder, an input, or standard output used twice. The first output decides the default
  /// report path, default_report_path(OUTPUT) (none when OUTPUT is "-", a device or a FIFO).
  /// Call before writing.
  void output(const std::string& path);
  /// The same for a Gmsh MSH output (every tool but meshconvert and meshplot writes MSH only):
  /// also throws InputError when the name has an extension other than .msh (sol.vtu would get
  /// MSH text that ParaView cannot read), naming meshconvert for the conversion. Names without
  /// an extension, "-", devices and FIFOs are accepted.
  void output_mesh(const std::string& path);
  /// The same for a JSON side output other than the report (lpcvt's --voronoi), named `what` in
  /// refusals: also throws InputError when the name has a mesh, picture or table extension
  /// (.msh, .vtu, .png, ...: JSON text would replace such a file), or when a non-empty regular
  /// file that is not a quadapt JSON (an object with a "tool" string) is in the way — a rerun
  /// replaces its own earlier output, never a file of the user's.
  void output_json(const std::string& path, const std::string& what);

  /// An option (its long name, e.g. "--title") whose empty value "" is meaningful: not refused
  /// as "empty value" (every other option given as "" is, exit 2).
  void allow_empty_value(const std::string& option) { may_be_empty_.push_back(option); }

  /// How a tool reads an input mesh: read_valid_msh(path, v) (exit 2 on what it refuses), then
  /// the checks that only warn (mesh/near_boundary.hpp: boundary edges lying on other boundary
  /// edges). Each warning is logged as "warning: PATH: ..." (not with -q, like every log line)
  /// and appended to report()["warnings"], a list present only when there is a warning.
  Mesh read_mesh(const std::string& path, const ValidateOptions& v = {});

  /// A warning: logged as "warning: MSG" (not with -q) and appended to report()["warnings"].
  void warn(const std::string& msg);

  /// The JSON report. Put computed figures at top level (e.g. report()["dofs"] = n);
  /// "tool", "version", "command", "options", "inputs", "outputs", "timings", "threads",
  /// "peak_memory_mb" are filled in by the runner.
  nlohmann::json& report() { return report_; }
  /// Records an effective option value in report()["options"][key].
  template <class T>
  void option(const std::string& key, const T& value) { report_["options"][key] = value; }

  /// Progress message on stderr ("name: msg"), unless -q.
  void log(const std::string& msg) const;
  bool quiet() const { return quiet_; }

  /// RAII phase timer: wall seconds are added to report()["timings"][phase].
  class Phase {
   public:
    Phase(Tool& t, std::string name);
    ~Phase();
    Phase(const Phase&) = delete;
    Phase& operator=(const Phase&) = delete;
   private:
    Tool& tool_;
    std::string name_;
    std::chrono::steady_clock::time_point start_;
  };
  Phase phase(const std::string& name) { return Phase(*this, name); }

  /// Writes the report now (atomically). run() calls this after a successful body, and after
  /// PartialFailure. A tool whose report goes to stdout (meshquality) calls set_report_path("-").
  void write_report();
  void set_report_path(const std::string& p);
  const std::string& report_path() const { return report_path_; }

  const std::string& name() const { return name_; }

 private:
  void declare_report();
  /// The JSON-output refusals shared by --report and output_json (see there), `what` naming the
  /// output in messages; `report`: the output is a tool report (messages say so); `allow_empty`:
  /// an empty file (mktemp's) may be replaced.
  static void refuse_foreign_json(const std::string& path, const std::string& what, bool report, const std::string& fix,
                                  bool allow_empty);
  static void use_stdio(const std::string& path, bool& used, const char* what);

  std::string name_;
  CLI::App app_;
  nlohmann::json report_;
  std::vector<std::string> inputs_;
  std::vector<std::string> outputs_;
  std::vector<std::string> may_be_empty_;  ///< allow_empty_value's options
  std::string report_path_;
  bool report_decided_ = false;
  bool report_explicit_ = false;  ///< --report given (or set_report_path), not beside the output
  bool stdin_used_ = false;
  bool stdout_used_ = false;
  bool quiet_ = false;
  int threads_ = 0;
  std::chrono::steady_clock::time_point start_;
  std::string start_date_;  ///< UTC, ISO 8601 (provenance)
};

/// The report beside an output: X.msh -> X.json; any other name gets .json appended (sol.vtu ->
/// sol.vtu.json, sol.png -> sol.png.json), so that converting or drawing sol.msh never replaces
/// the sol.json its solver wrote.
std::string default_report_path(const std::string& output);

/// Peak resident memory of this process in MiB (from /proc/self/status VmHWM).
double peak_memory_mb();

}  // namespace quadapt
