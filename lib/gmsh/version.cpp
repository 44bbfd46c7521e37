#include "gmsh/version.hpp"

#include <gmsh.h>

namespace quadapt {
const char* gmsh_api_version() { return GMSH_API_VERSION; }
}  // namespace quadapt
