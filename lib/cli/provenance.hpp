#pragma once
// Provenance of a tool run: what was built (git commit and "dirty", build type, compiler,
// library versions; cli/build_info.hpp) and where and on what it ran (UTC date, host CPU, the
// sha256 of every input file). `--version` prints the first; every report carries both under
// "provenance" (docs/file-formats.md §3).
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace quadapt {

/// The --version text of tool `name`, several lines:
///   NAME (quadapt) 0.1.0
///   commit 0123abcd... (dirty)        or "commit unknown (built without git)"
///   build Release, GNU 12.2.0
///   libraries: gmsh 4.8.0, CGAL 5.5.1, Eigen 3.4.0, ...
std::string version_text(const std::string& name);

/// {"commit", "dirty", "describe", "build_type", "compiler", "libraries": {name: version}}.
nlohmann::json build_provenance();

/// The current UTC time as ISO 8601 ("2026-11-24T15:47:04Z").
std::string utc_now_iso8601();

/// {"cpu": model name from /proc/cpuinfo, "logical_cores": n, "system": "Linux 6.1.0 x86_64"}.
nlohmann::json host_provenance();

/// {path: sha256} of the inputs that are regular files (others, e.g. "-", map to null).
nlohmann::json input_checksums(const std::vector<std::string>& inputs);

}  // namespace quadapt
