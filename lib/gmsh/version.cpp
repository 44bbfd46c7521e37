#include "gmsh/version.hpp"

#include <gmsh.h>

#ifndef QUADAPT_GMSH_LIBRARY_VERSION
#define QUADAPT_GMSH_LIBRARY_VERSION ""
#endif

namespace quadapt {
const char* gmsh_api_version() { return GMSH_API_VERSION; }
const char* gmsh_library_version() {
  static const char* const v = QUADAPT_GMSH_LIBRARY_VERSION;
  return v[0] != '\0' ? v : GMSH_API_VERSION;
}
}  // namespace quadapt
