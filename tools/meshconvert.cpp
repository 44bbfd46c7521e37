// meshconvert IN.msh -o OUT.(msh|vtu) [--require quads|triangles]: read any supported MSH, validate,
// write MSH 4.1 ASCII or VTK XML for ParaView (with every field).
#include "cli/tool.hpp"
#include "io/msh.hpp"
#include "io/vtu.hpp"
#include "mesh/validate.hpp"

using namespace quadapt;

int main(int argc, char** argv) {
  Tool tool("meshconvert", "Convert a Gmsh mesh (MSH 2.2 / 4.1, ASCII / binary) to validated MSH 4.1 ASCII",
            "Reads IN with its fields ($ElementData, $ElementNodeData), completes a missing boundary from the "
            "free edges (curves split at corners, named bottom/right/top/left on the unit square, else "
            "boundary_1..n), validates it (element type with --require, inverted or degenerate cells, boundary "
            "edges on the boundary, non-finite coordinates) and writes OUT atomically as MSH 4.1 ASCII that "
            "reads back bit-exactly, or, when OUT ends in .vtu, as VTK XML for ParaView (the DG solution u as Lagrange "
            "quadrilaterals of degree p, cell fields as cell data, Vinv as a 3x3 tensor). Nothing is written when IN "
            "is invalid. Formats: docs/file-formats.md.");
  std::string in, out, require = "any";
  tool.app().add_option("IN", in, "Input mesh (.msh)")->required()->check(CLI::ExistingFile);
  tool.app().add_option("-o,--output", out, "Output mesh: .msh (MSH 4.1 ASCII) or .vtu (VTK XML, ParaView)")->required();
  tool.app()
      .add_option("--require", require, "Element type IN must consist of: any, quads or triangles")
      ->check(CLI::IsMember({"any", "quads", "triangles"}))
      ->capture_default_str();
  return tool.run(argc, argv, [&] {
    tool.input(in);
    tool.output(out);
    ValidateOptions opt;
    opt.require = require == "quads" ? CellKind::Quads : require == "triangles" ? CellKind::Triangles : CellKind::Any;
    opt.allow_curved = true;  // curved quads are converted with their high-order nodes
    Mesh m;
    {
      auto ph = tool.phase("read");
      m = read_valid_msh(in, opt);
    }
    {
      auto ph = tool.phase("write");
      write_mesh_file(m, out);
    }
    tool.report()["nodes"] = m.num_nodes();
    tool.report()["cells"] = m.num_cells();
    tool.report()["quads"] = m.num_quads();
    tool.report()["triangles"] = m.num_triangles();
    tool.report()["geometric_order"] = m.geometric_order();
    tool.report()["boundary_edges"] = m.boundary.size();
    nlohmann::json fields = nlohmann::json::array();
    for (const auto& f : m.cell_fields) fields.push_back(f.name);
    for (const auto& f : m.cell_node_fields) fields.push_back(f.name);
    tool.report()["fields"] = fields;
  });
}
