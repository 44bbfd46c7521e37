#pragma once
// What was built: filled in by cmake/build_info.cmake on every build (the source is generated in
// the build tree), so --version and the reports name the exact commit.

namespace quadapt {

struct BuildInfo {
  const char* version;     ///< project version (CMakeLists.txt)
  const char* commit;      ///< full git commit hash, or "unknown" (no .git, e.g. a tarball)
  bool dirty;              ///< tracked files differed from the commit when it was built
  const char* describe;    ///< `git describe --always --dirty --tags`, or ""
  const char* build_type;  ///< CMAKE_BUILD_TYPE (Release, Debug, ...)
  const char* compiler;    ///< compiler id and version
  const char* lbfgspp;     ///< LBFGSpp has no version macro: the Debian package's, or "unknown"
};

const BuildInfo& build_info();

}  // namespace quadapt
