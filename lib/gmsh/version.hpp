#pragma once
// The Gmsh versions quadapt was built with, for provenance (cli/provenance.hpp).
namespace quadapt {
/// The Gmsh SDK's API version, gmsh.h's GMSH_API_VERSION (Debian's Gmsh 4.8.4 says 4.8.0).
const char* gmsh_api_version();
/// The Gmsh library's version, from the file the build linked (libgmsh.so.4.8.4 -> "4.8.4"); the
/// API version when the file name carries none.
const char* gmsh_library_version();
}  // namespace quadapt
