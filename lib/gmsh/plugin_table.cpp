// The plugin's entry point (gmsh/plugin.hpp): built into libquadapt-gmsh.so only.
#include "gmsh/plugin.hpp"

extern "C" const quadapt::gmsh_plugin::Table* quadapt_gmsh_plugin_table() {
  static const quadapt::gmsh_plugin::Table table{quadapt::gmsh_plugin::kAbi, &quadapt::gmsh_plugin::sdk_open_geometry,
                                                 &quadapt::gmsh_plugin::sdk_gmsh_recombine};
  return &table;
}
