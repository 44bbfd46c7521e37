// cli/tool: the runner's exit codes, report, output declarations and option checks.
#include <doctest/doctest.h>
#include <omp.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <vector>

#include "cli/option_ranges.hpp"
#include "cli/tool.hpp"
#include "core/atomic_file.hpp"
#include "core/path_guard.hpp"
#include "../temp_dir.hpp"

using namespace quadapt;
namespace fs = std::filesystem;

namespace {
// The guard is process-wide: leave it off and empty for the next test.
struct GuardReset {
  ~GuardReset() {
    clear_protected_paths();
    enable_input_guard(false);
  }
};
struct Dir : quadapt::test::TempDir, GuardReset {};

// Runs a Tool "t" with `args` (argv[0] added) and an option --x (double) and -o.
int run(std::vector<std::string> args, const std::function<void(Tool&, const std::string&)>& body,
        double* x_out = nullptr) {
  Tool tool("t", "test tool");
  std::string out;
  double x = 1;
  tool.app().add_option("-o", out);
  tool.app().add_option("--rtol", x);
  args.insert(args.begin(), "t");
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  const int rc = tool.run(static_cast<int>(argv.size()), argv.data(), [&] { body(tool, out); });
  if (x_out) *x_out = x;
  return rc;
}
}  // namespace

TEST_CASE("exit codes: 0 ok, 1 PartialFailure (report kept), 2 bad input / parse, 3 internal") {
  Dir t;
  auto write = [](Tool& tool, const std::string& out) {
    tool.output(out);
    atomic_write(out, [](std::ostream& os) { os << "mesh"; });
  };
  CHECK(run({"-o", t / "a.msh"}, write) == 0);
  CHECK(fs::exists(t / "a.json"));
  const auto rep = nlohmann::json::parse(read_text_file(t / "a.json"));
  CHECK(rep["tool"] == "t");
  CHECK(rep["outputs"][0] == t / "a.msh");
  CHECK(rep["threads"].get<int>() >= 1);

  CHECK(run({"-o", t / "b.msh"}, [&](Tool& tool, const std::string& out) {
          write(tool, out);
          throw PartialFailure("not converged");
        }) == 1);
  CHECK(fs::exists(t / "b.json"));
  CHECK(run({"-o", t / "c.msh"}, [](Tool&, const std::string& out) { throw InputError(out, "bad"); }) == 2);
  CHECK(run({"-o", t / "c.msh"}, [](Tool&, const std::string&) { throw std::logic_error("bug"); }) == 3);
  CHECK(run({"--bogus"}, [](Tool&, const std::string&) {}) == 2);
  CHECK(!fs::exists(t / "c.json"));
}

TEST_CASE("option checks at parse time: finite, ranges; threads clamped") {
  Dir t;
  bool ran = false;
  auto body = [&](Tool&, const std::string&) { ran = true; };
  for (const char* bad : {"-1", "0", "1", "nan", "inf"}) {
    CAPTURE(bad);
    ran = false;
    CHECK(run({"--rtol", bad}, body) == 2);
    CHECK(!ran);
  }
  double x = 0;
  CHECK(run({"--rtol", "1e-3"}, body, &x) == 0);
  CHECK(x == 1e-3);
  CHECK(run({"--threads", "100000"}, body) == 0);
  CHECK(omp_get_max_threads() <= 4 * omp_get_num_procs());
  CHECK(clamp_threads(100000) == 4 * omp_get_num_procs());
  CHECK(clamp_threads(1) == 1);
  CHECK(run({"--threads", "-2"}, body) == 2);
}

TEST_CASE("outputs: never an input (either order), '' and a directory refused, '-' has no default report") {
  Dir t;
  std::ofstream(t / "in.msh") << "x";
  auto in_then_out = [&](Tool& tool, const std::string& out) {
    tool.input(t / "in.msh");
    tool.output(out);
  };
  auto out_then_in = [&](Tool& tool, const std::string& out) {
    tool.output(out);
    tool.input(t / "in.msh");
  };
  CHECK(run({"-o", t / "in.msh"}, in_then_out) == 2);
  CHECK(run({"-o", t / "in.msh"}, out_then_in) == 2);
  CHECK(run({"-o", t / "x.msh", "--report", t / "in.msh"}, out_then_in) == 2);
  CHECK(run({"-o", t / "x.msh", "--report", t / "in.msh"}, in_then_out) == 2);
  CHECK(!fs::exists(t / "x.json"));
  CHECK(run({"-o", ""}, in_then_out) == 2);
  CHECK(run({"-o", t.dir.string()}, in_then_out) == 2);
  CHECK(run({"-o", "-"}, [](Tool& tool, const std::string& out) {
          tool.output(out);
          CHECK(tool.report_path().empty());
        }) == 0);
  CHECK(run({"-o", "-", "--report", "-"}, [](Tool& tool, const std::string& out) { tool.output(out); }) == 2);
}
