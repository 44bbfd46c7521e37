#include "io/gmsh_options.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <sstream>

#include "core/atomic_file.hpp"

namespace quadapt {

namespace {
const char* const kHeader = "// Gmsh options written by quadapt (lib/io/gmsh_options.hpp): smooth high-order display.\n";
}

std::string gmsh_view_options(const Mesh& m) {
  std::ostringstream o;
  const int nf = static_cast<int>(m.cell_fields.size());
  const int nviews = nf + static_cast<int>(m.cell_node_fields.size());
  bool any = false;
  for (size_t k = 0; k < m.cell_node_fields.size(); ++k) {
    const CellNodeField& f = m.cell_node_fields[k];
    if (f.degree < 1) continue;
    if (!any) o << kHeader;
    any = true;
    const int i = nf + static_cast<int>(k);
    int level = 1;
    while ((1 << level) < 2 * f.degree) ++level;
    const double cells = std::max(1, m.num_cells());
    while (level > 1 && cells * std::pow(4.0, level) > 4e6) --level;
    // the file's views are the last nviews Gmsh holds when it merges this file (other files
    // opened before it come first): index them from PostProcessing.NbViews, not from 0
    std::ostringstream idx;
    idx << "View[PostProcessing.NbViews - " << (nviews - i) << "]";
    o << idx.str() << ".AdaptVisualizationGrid = 1;\n"
      << idx.str() << ".MaxRecursionLevel = " << level << ";\n"
      << idx.str() << ".TargetError = -1;\n";
  }
  return any ? o.str() : "";
}

void stage_gmsh_options(const Mesh& mesh, const std::string& msh_path, OutputBatch& batch) {
  namespace fs = std::filesystem;
  if (msh_path.empty() || msh_path == "-" || msh_path.rfind("/dev/", 0) == 0) return;
  std::error_code ec;
  const fs::file_status st = fs::status(msh_path, ec);
  if (!ec && fs::exists(st) && !fs::is_regular_file(st)) return;
  const std::string opt = msh_path + ".opt";
  const std::string text = gmsh_view_options(mesh);
  if (text.empty()) {
    // a stale options file of ours removed once the mesh is replaced
    batch.after_commit([opt] {
      std::ifstream in(opt);
      std::string first;
      if (in && std::getline(in, first) && first + "\n" == kHeader) {
        in.close();
        std::error_code e;
        fs::remove(opt, e);
      }
    });
    return;
  }
  batch.add(opt, [text](std::ostream& out) { out << text; });
}

}  // namespace quadapt
