#pragma once
// A fresh temporary directory for a unit test, removed with its contents at scope exit.
#include <doctest/doctest.h>
#include <stdlib.h>

#include <filesystem>
#include <iterator>
#include <string>

namespace quadapt::test {

struct TempDir {
  std::filesystem::path dir;
  TempDir() {
    std::string t = (std::filesystem::temp_directory_path() / "quadapt-test-XXXXXX").string();
    REQUIRE(mkdtemp(t.data()));
    dir = t;
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  /// The path of `name` inside the directory.
  std::string operator/(const std::string& name) const { return (dir / name).string(); }
  /// Number of entries in the directory.
  size_t entries() const {
    return std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator());
  }
};

}  // namespace quadapt::test
