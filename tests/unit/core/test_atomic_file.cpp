// core/atomic_file and core/path_guard: what an output path means (regular file, symlink, FIFO,
// device, "-", "", directory) and the never-overwrite-an-input check through links and "..".
#include <doctest/doctest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/path_guard.hpp"
#include "../temp_dir.hpp"

using namespace quadapt;
using quadapt::test::TempDir;
namespace fs = std::filesystem;

namespace {
std::string slurp(const std::string& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}
void put(const std::string& p, const std::string& text) {
  std::ofstream(p) << text;
}
}  // namespace

TEST_CASE("atomic_write replaces a regular file; a failing writer leaves the old file and no temporary") {
  TempDir t;
  put(t / "a.txt", "old");
  atomic_write(t / "a.txt", [](std::ostream& os) { os << "new"; });
  CHECK(slurp(t / "a.txt") == "new");
  CHECK_THROWS_AS(atomic_write(t / "a.txt", [](std::ostream& os) { os << "half"; throw std::runtime_error("boom"); }),
                  std::runtime_error);
  CHECK(slurp(t / "a.txt") == "new");
  CHECK(t.entries() == 1);
}

// OutputBatch: several outputs replaced as one (a mesh and its .opt, lpcvt's side outputs): a
// failure in any add() replaces none of them and leaves no temporary; commit() replaces all, then
// runs the after_commit steps.
TEST_CASE("OutputBatch: all or nothing") {
  TempDir t;
  put(t / "a.txt", "old a");
  put(t / "b.txt", "old b");
  {
    OutputBatch b;
    b.add(t / "a.txt", [](std::ostream& os) { os << "new a"; });
    CHECK(slurp(t / "a.txt") == "old a");  // nothing replaced before commit
    CHECK_THROWS_AS(b.add(t / "b.txt", [](std::ostream& os) { os << "half"; throw std::runtime_error("boom"); }),
                    std::runtime_error);
  }  // the batch dropped without commit
  CHECK(slurp(t / "a.txt") == "old a");
  CHECK(slurp(t / "b.txt") == "old b");
  CHECK(t.entries() == 2);  // no temporaries
  bool after = false;
  {
    OutputBatch b;
    b.add(t / "a.txt", [](std::ostream& os) { os << "new a"; });
    b.add(t / "c.txt", [](std::ostream& os) { os << "new c"; });
    b.after_commit([&] { after = fs::exists(std::string(t / "c.txt")); });
    b.commit();
  }
  CHECK(after);  // after the renames
  CHECK(slurp(t / "a.txt") == "new a");
  CHECK(slurp(t / "c.txt") == "new c");
  CHECK(t.entries() == 3);
  // a device that fails (/dev/full) is written before any rename: the regular target is kept
  if (::access("/dev/full", W_OK) == 0) {
    OutputBatch b;
    b.add(t / "a.txt", [](std::ostream& os) { os << "newer a"; });
    b.add("/dev/full", [](std::ostream& os) { os << std::string(1 << 16, 'x'); });
    CHECK_THROWS_AS(b.commit(), ExternalError);
    CHECK(slurp(t / "a.txt") == "new a");
  }
}

TEST_CASE("resolve_output classifies paths") {
  TempDir t;
  CHECK(resolve_output("-").kind == OutputTarget::Kind::Stdout);
  CHECK_THROWS_AS(resolve_output(""), InputError);
  CHECK_THROWS_WITH_AS(resolve_output(t.dir.string()), doctest::Contains("is a directory"), InputError);
  CHECK_THROWS_WITH_AS(resolve_output(t / "no/such.msh"), doctest::Contains("does not exist"), InputError);
  CHECK(resolve_output(t / "new.msh").kind == OutputTarget::Kind::Regular);
  CHECK(resolve_output("/dev/null").kind == OutputTarget::Kind::Special);
  fs::create_symlink("loop2", t / "loop1");
  fs::create_symlink("loop1", t / "loop2");
  CHECK_THROWS_AS(resolve_output(t / "loop1"), InputError);
}

TEST_CASE("a symlink is written through to its target, dangling or not") {
  TempDir t;
  put(t / "target.txt", "old");
  fs::create_symlink("target.txt", t / "link.txt");
  atomic_write(t / "link.txt", [](std::ostream& os) { os << "new"; });
  CHECK(fs::is_symlink(t / "link.txt"));
  CHECK(slurp(t / "target.txt") == "new");
  fs::create_symlink("made.txt", t / "dangling.txt");
  atomic_write(t / "dangling.txt", [](std::ostream& os) { os << "made"; });
  CHECK(fs::is_symlink(t / "dangling.txt"));
  CHECK(slurp(t / "made.txt") == "made");
}

TEST_CASE("a FIFO is written directly (a reader sees every byte, the FIFO stays)") {
  TempDir t;
  REQUIRE(mkfifo((t / "p").c_str(), 0600) == 0);
  std::string got;
  std::thread reader([&] { got = slurp(t / "p"); });
  atomic_write(t / "p", [](std::ostream& os) { os << "through the pipe"; });
  reader.join();
  CHECK(got == "through the pipe");
  struct stat st {};
  REQUIRE(stat((t / "p").c_str(), &st) == 0);
  CHECK(S_ISFIFO(st.st_mode));
}

TEST_CASE("atomic_write_via_path: the writer's file is renamed over the target") {
  TempDir t;
  atomic_write_via_path(t / "x.dat", [](const std::string& tmp) {
    CHECK(fs::path(tmp).extension() == ".dat");
    put(tmp, "via");
  });
  CHECK(slurp(t / "x.dat") == "via");
  CHECK_THROWS_AS(atomic_write_via_path(t / "y.dat", [](const std::string&) {}), ExternalError);
  CHECK(t.entries() == 1);
}

TEST_CASE("path_guard: an output may not be an input through a name, .., a symlink or a hard link") {
  TempDir t;
  put(t / "in.msh", "input");
  fs::create_directory(t / "d");
  fs::create_symlink("in.msh", t / "sym.msh");
  fs::create_hard_link(t / "in.msh", t / "hard.msh");
  CHECK(same_file(t / "in.msh", t / "d/../in.msh"));
  CHECK(same_file(t / "in.msh", t / "hard.msh"));
  CHECK(!same_file(t / "in.msh", t / "other.msh"));

  clear_protected_paths();
  enable_input_guard(false);
  protect_input(t / "in.msh");  // guard off: nothing recorded
  CHECK_NOTHROW(check_not_an_input(t / "in.msh"));

  enable_input_guard(true);
  protect_input(t / "in.msh");
  for (const char* name : {"in.msh", "d/../in.msh", "sym.msh", "hard.msh"}) {
    CAPTURE(name);
    CHECK_THROWS_WITH_AS(protect_output(t / name), doctest::Contains("would overwrite the input file"), InputError);
    CHECK_THROWS_AS(atomic_write(t / name, [](std::ostream& os) { os << "x"; }), InputError);
  }
  CHECK(slurp(t / "in.msh") == "input");
  CHECK_NOTHROW(protect_output(t / "out.msh"));
  CHECK_THROWS_WITH_AS(protect_output(t / "d/../out.msh"), doctest::Contains("given twice"), InputError);
  // declared in the other order: an output first, then the same file as an input
  put(t / "late.msh", "x");
  CHECK_NOTHROW(protect_output(t / "late.msh"));
  CHECK_THROWS_AS(protect_input(t / "late.msh"), InputError);
  // read_text_file records what it reads
  put(t / "case.json", "{}");
  CHECK(read_text_file(t / "case.json") == "{}");
  CHECK_THROWS_AS(check_not_an_input(t / "case.json"), InputError);
  clear_protected_paths();
  enable_input_guard(false);
}
