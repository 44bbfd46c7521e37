// read_valid_msh: read + validate in one call, every rejection an InputError "PATH: problem".
#include <doctest/doctest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "core/error.hpp"
#include "io/msh.hpp"

using namespace quadapt;

namespace {
const std::string kGood = std::string(QUADAPT_SOURCE_DIR) + "/tests/golden/io/square2_fields.msh";
std::string good_text() {
  std::ifstream in(kGood);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}
// Writes `text` to a temporary .msh and returns its path (removed at exit of the test process).
std::string temp_msh(const std::string& text) {
  std::string t = (std::filesystem::temp_directory_path() / "quadapt-rv-XXXXXX.msh").string();
  const int fd = mkstemps(t.data(), 4);
  REQUIRE(fd >= 0);
  close(fd);
  std::ofstream(t) << text;
  return t;
}
}  // namespace

TEST_CASE("read_valid_msh accepts a valid mesh and applies the options") {
  Mesh m = read_valid_msh(kGood);
  CHECK(m.num_cells() == 4);
  CHECK_NOTHROW(read_valid_msh(kGood, ValidateOptions::cells(CellKind::Quads)));
  CHECK_THROWS_WITH_AS(read_valid_msh(kGood, ValidateOptions::cells(CellKind::Triangles)),
                       doctest::Contains("square2_fields.msh: "), InputError);
  CHECK_THROWS_WITH_AS(read_valid_msh(kGood, ValidateOptions::fields({"dwr"})), doctest::Contains("'dwr' not found"),
                       InputError);
}

TEST_CASE("read_valid_msh rejects, naming the file: inverted cell, NaN field value, missing file") {
  const std::string text = good_text();
  // cell 1 with its corners in clockwise order
  const std::string inv = std::regex_replace(text, std::regex("\n1 1 2 5 4\n"), "\n1 1 4 5 2\n");
  REQUIRE(inv != text);
  const std::string p1 = temp_msh(inv);
  CHECK_THROWS_WITH_AS(read_valid_msh(p1), doctest::Contains((p1 + ": ").c_str()), InputError);
  // a NaN in the cell field h
  const std::string nan = std::regex_replace(text, std::regex("\n2 0.25\n"), "\n2 nan\n");
  REQUIRE(nan != text);
  const std::string p2 = temp_msh(nan);
  CHECK_NOTHROW(read_msh(p2));  // the reader keeps what the file says...
  CHECK_THROWS_WITH_AS(read_valid_msh(p2), doctest::Contains("field 'h' is not finite in cell 2"), InputError);
  CHECK_THROWS_WITH_AS(read_valid_msh("/no/such/file.msh"), doctest::Contains("/no/such/file.msh: cannot open"),
                       InputError);
  std::filesystem::remove(p1);
  std::filesystem::remove(p2);
}
