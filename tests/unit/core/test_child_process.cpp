// core/child_process: run_child's exit statuses, output file, working directory and a program
// that cannot be started; on_path; TempFile's removal (core/atomic_file.hpp).
#include <doctest/doctest.h>

#include <cerrno>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/atomic_file.hpp"
#include "core/child_process.hpp"
#include "../temp_dir.hpp"

using namespace quadapt;
using quadapt::test::TempDir;
namespace fs = std::filesystem;

TEST_CASE("run_child: exit status, output file, working directory; a missing program is a spawn error") {
  TempDir t;
  ChildOptions o;
  o.output = t / "out.txt";
  o.directory = t.dir.string();
  const ChildExit ok = run_child({"sh", "-c", "pwd; echo err >&2"}, o);
  CHECK(ok.ok());
  std::ifstream in(o.output);
  std::stringstream ss;
  ss << in.rdbuf();
  CHECK(ss.str() == fs::canonical(t.dir).string() + "\nerr\n");  // stdout and stderr, in its directory

  const ChildExit three = run_child({"sh", "-c", "exit 3"});
  CHECK_FALSE(three.ok());
  CHECK(three.how() == "exit status 3");
  const ChildExit killed = run_child({"sh", "-c", "kill -TERM $$"});
  CHECK(killed.how() == "signal 15");

  const ChildExit missing = run_child({"quadapt-no-such-program"});
  CHECK(missing.spawn_error == ENOENT);
  CHECK_FALSE(missing.ok());
}

TEST_CASE("on_path: programs on PATH and executable paths") {
  CHECK(on_path("sh"));
  CHECK_FALSE(on_path("quadapt-no-such-program"));
  CHECK(on_path("/bin/sh"));
  CHECK_FALSE(on_path("/etc/passwd"));  // not executable
}

TEST_CASE("TempFile: removed at scope exit unless released") {
  TempDir t;
  {
    const TempFile f(t / "a.tmp");
    std::ofstream(f.path()) << "x";
    CHECK(fs::exists(f.path()));
  }
  CHECK_FALSE(fs::exists(t / "a.tmp"));
  {
    TempFile f(t / "b.tmp");
    std::ofstream(f.path()) << "x";
    f.release();
  }
  CHECK(fs::exists(t / "b.tmp"));
}
