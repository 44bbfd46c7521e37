// libquadapt's side of the Gmsh plugin (gmsh/plugin.hpp): open_geometry() and gmsh_recombine()
// load libquadapt-gmsh.so on their first call and forward to it.
#include <dlfcn.h>

#include <string>

#include "core/error.hpp"
#include "gmsh/plugin.hpp"

namespace quadapt {

namespace gmsh_plugin {

namespace {

/// The directory of the object holding this function (libquadapt.so), with a trailing '/'.
std::string own_directory() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&own_directory), &info) == 0 || info.dli_fname == nullptr) return "";
  std::string path = info.dli_fname;
  const auto slash = path.rfind('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

const Table* load() {
  const std::string path = own_directory() + kFileName;
  void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* error = dlerror();
    std::string why = error ? error : "unknown error";
    if (why.rfind(path + ": ", 0) == 0) why.erase(0, path.size() + 2);  // glibc starts with the path
    throw ExternalError("Gmsh support: cannot load " + path + ": " + why +
                        " (" + kFileName + " must sit beside libquadapt.so, and libgmsh be installed)");
  }
  using Entry = const Table* (*)();
  auto entry = reinterpret_cast<Entry>(dlsym(handle, kEntry));
  if (!entry) throw ExternalError("Gmsh support: " + path + " has no entry point " + kEntry);
  const Table* t = entry();
  if (!t || t->abi != kAbi || !t->open_geometry || !t->recombine)
    throw ExternalError("Gmsh support: " + path + " is from another quadapt build (plugin version " +
                        std::to_string(t ? t->abi : -1) + ", expected " + std::to_string(kAbi) + ")");
  return t;
}

}  // namespace

const Table& table() {
  static const Table* const t = load();  // a failed load throws and is retried by the next call
  return *t;
}

}  // namespace gmsh_plugin

std::unique_ptr<BoundaryGeometry> open_geometry(const std::string& path) {
  return gmsh_plugin::table().open_geometry(path);
}

GmshRecombined gmsh_recombine(const Mesh& tri, const std::vector<std::vector<int>>& loops,
                              const std::vector<char>& on_boundary, const GmshRecombineOptions& opt) {
  return gmsh_plugin::table().recombine(tri, loops, on_boundary, opt);
}

}  // namespace quadapt
