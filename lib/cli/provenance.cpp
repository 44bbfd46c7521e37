#include "cli/provenance.hpp"

#include <sys/utsname.h>
#include <umfpack.h>

#include <CGAL/version.h>
#include <CLI/Version.hpp>
#include <Eigen/Core>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "cli/build_info.hpp"
#include "core/sha256.hpp"
#include "core/standard_input.hpp"
#include "gmsh/version.hpp"

namespace quadapt {

namespace {
#define QUADAPT_STR2(x) #x
#define QUADAPT_STR(x) QUADAPT_STR2(x)

std::vector<std::pair<std::string, std::string>> libraries() {
  return {
      {"gmsh", gmsh_library_version()},
      {"CGAL", QUADAPT_STR(CGAL_VERSION)},
      {"Eigen", std::to_string(EIGEN_WORLD_VERSION) + "." + std::to_string(EIGEN_MAJOR_VERSION) + "." +
                    std::to_string(EIGEN_MINOR_VERSION)},
      {"UMFPACK", std::to_string(UMFPACK_MAIN_VERSION) + "." + std::to_string(UMFPACK_SUB_VERSION) + "." +
                      std::to_string(UMFPACK_SUBSUB_VERSION)},
      {"CLI11", CLI11_VERSION},
      {"nlohmann_json", std::to_string(NLOHMANN_JSON_VERSION_MAJOR) + "." + std::to_string(NLOHMANN_JSON_VERSION_MINOR) +
                            "." + std::to_string(NLOHMANN_JSON_VERSION_PATCH)},
      {"LBFGSpp", build_info().lbfgspp},
#ifdef _OPENMP
      {"OpenMP", QUADAPT_STR(_OPENMP)},
#endif
      {"gmsh_api", gmsh_api_version()},  // gmsh.h's, beside the library's above (4.8.0 in Gmsh 4.8.4)
  };
}
}  // namespace

std::string version_text(const std::string& name) {
  const BuildInfo& b = build_info();
  std::ostringstream o;
  o << name << " (quadapt) " << b.version << "\n";
  if (std::string(b.commit) == "unknown")
    o << "commit unknown (built without git)\n";
  else
    o << "commit " << b.commit << (b.dirty ? " (dirty: uncommitted changes were built)" : "") << "\n";
  o << "build " << b.build_type << ", " << b.compiler << "\n";
  o << "libraries:";
  bool first = true;
  for (const auto& [lib, v] : libraries()) {
    o << (first ? " " : ", ") << lib << " " << v;
    first = false;
  }
  return o.str();
}

nlohmann::json build_provenance() {
  const BuildInfo& b = build_info();
  nlohmann::json j;
  j["commit"] = b.commit;
  j["dirty"] = b.dirty;
  j["describe"] = b.describe;
  j["build_type"] = b.build_type;
  j["compiler"] = b.compiler;
  for (const auto& [lib, v] : libraries()) j["libraries"][lib] = v;
  return j;
}

std::string utc_now_iso8601() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

nlohmann::json host_provenance() {
  nlohmann::json j;
  std::string cpu = "unknown";
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("model name", 0) == 0) {
      const size_t c = line.find(':');
      if (c != std::string::npos) cpu = line.substr(line.find_first_not_of(" \t", c + 1));
      break;
    }
  }
  j["cpu"] = cpu;
  j["logical_cores"] = std::thread::hardware_concurrency();
  utsname u{};
  if (uname(&u) == 0) j["system"] = std::string(u.sysname) + " " + u.release + " " + u.machine;
  return j;
}

nlohmann::json input_checksums(const std::vector<std::string>& inputs) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& p : inputs) {
    std::error_code ec;
    if (p == "-") {
      const auto h = standard_input_sha256();  // null only when nothing was read from it
      j[p] = h ? nlohmann::json(*h) : nlohmann::json(nullptr);
    } else if (std::filesystem::is_regular_file(p, ec)) {
      j[p] = sha256_file(p);
    } else {
      j[p] = nullptr;
    }
  }
  return j;
}

}  // namespace quadapt
