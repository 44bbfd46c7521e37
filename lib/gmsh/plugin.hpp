#pragma once
// Gmsh support as a plugin, loaded on first use. libgmsh pulls in ~90 shared libraries
// (OpenCASCADE, FLTK, X11, ...) whose relocations the dynamic loader resolves at start-up
// (BIND_NOW): ~0.1 s for every process that links it, though only bamgquad, recombine's
// Blossom mode and the --geometry options call Gmsh. So the SDK-backed code of lib/gmsh
// (session.cpp, geometry.cpp, gmsh_recombine.cpp) is built into its own library,
// libquadapt-gmsh.so, installed beside libquadapt.so; libquadapt's open_geometry() and
// gmsh_recombine() load it with dlopen on their first call (loader.cpp) and call through the
// table below. docs/design.md §6.
#include <memory>
#include <string>
#include <vector>

#include "gmsh/geometry.hpp"
#include "gmsh/gmsh_recombine.hpp"

namespace quadapt::gmsh_plugin {

/// The table's layout version: the loader refuses a plugin built with another one.
constexpr int kAbi = 1;

/// The plugin's entry points (its functions open_geometry / gmsh_recombine, documented in
/// gmsh/geometry.hpp and gmsh/gmsh_recombine.hpp).
struct Table {
  int abi = kAbi;
  std::unique_ptr<BoundaryGeometry> (*open_geometry)(const std::string& path) = nullptr;
  GmshRecombined (*recombine)(const Mesh& tri, const std::vector<std::vector<int>>& loops,
                              const std::vector<char>& on_boundary, const GmshRecombineOptions& opt) = nullptr;
};

/// The plugin's file name, looked up in the directory of libquadapt.so.
constexpr const char* kFileName = "libquadapt-gmsh.so";
/// The symbol the plugin exports (extern "C", returns a pointer to its Table).
constexpr const char* kEntry = "quadapt_gmsh_plugin_table";

/// Loads the plugin on the first call (thread-safe; never unloaded) and returns its table.
/// Throws ExternalError naming the file and what to fix when it cannot be loaded.
const Table& table();

// The plugin's implementations (defined in the plugin library only).
std::unique_ptr<BoundaryGeometry> sdk_open_geometry(const std::string& path);
GmshRecombined sdk_gmsh_recombine(const Mesh& tri, const std::vector<std::vector<int>>& loops,
                                  const std::vector<char>& on_boundary, const GmshRecombineOptions& opt);

}  // namespace quadapt::gmsh_plugin

extern "C" const quadapt::gmsh_plugin::Table* quadapt_gmsh_plugin_table();
