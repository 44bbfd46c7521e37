#pragma once
// The Gmsh SDK version quadapt was compiled against (gmsh.h's GMSH_API_VERSION), for provenance.
namespace quadapt {
const char* gmsh_api_version();
}
