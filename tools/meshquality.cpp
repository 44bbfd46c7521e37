// meshquality MESH.msh [--frame FRAME.msh] [--require quads|triangles]: quality figures as JSON.
#include "cli/tool.hpp"
#include "io/msh.hpp"
#include "mesh/validate.hpp"
#include "quality/mesh_quality.hpp"

using namespace quadapt;

int main(int argc, char** argv) {
  Tool tool("meshquality", "Mesh quality figures (angles, scaled Jacobians, metric edge lengths) as JSON on stdout",
            "Reads MESH (Gmsh MSH 4.1 or 2.2, ASCII or binary), validates it and prints a JSON report on stdout "
            "(or to --report FILE): counts by element type, total area, boundary groups with their edge counts, "
            "and in 'physical' the minimum / maximum / mean interior angle, the share of quad angles within "
            "90 +- 10 degrees, the minimum and mean scaled Jacobian, the median edge ratio and orientation of "
            "the quads. With --frame FRAME.msh (a background mesh with the per-cell frame 'Vinv', M = V^-1 in "
            "the upper-left 2x2) the same figures in the frame's metric space ('metric': each cell mapped by the "
            "M of the background cell containing its centroid), metric edge lengths (1 = the target edge; share "
            "within [1/sqrt2, sqrt2]) and, in 'frame', the frame's continuous element count beside the actual "
            "count. The frame file states its size convention ($FrameConvention; none = PHiLiP's full-edge sizes). Definitions: docs/meshquality.md.");
  std::string in, frame_path, require = "any";
  tool.app().add_option("MESH", in, "Mesh to measure (.msh)")->required()->check(CLI::ExistingFile);
  tool.app().add_option("--frame", frame_path, "Frame file: background mesh with the cell field Vinv")
      ->check(CLI::ExistingFile);
  tool.app()
      .add_option("--require", require, "Element type MESH must consist of: any, quads or triangles")
      ->check(CLI::IsMember({"any", "quads", "triangles"}))
      ->capture_default_str();
  tool.app().get_option("--report")->description("JSON report path (default: standard output)");
  return tool.run(argc, argv, [&] {
    tool.input(in);
    if (!frame_path.empty()) tool.input(frame_path);
    if (tool.report_path().empty()) tool.set_report_path("-");
    ValidateOptions opt;
    opt.require = require == "quads" ? CellKind::Quads : require == "triangles" ? CellKind::Triangles : CellKind::Any;
    opt.allow_curved = true;  // measured on the curved map (docs/meshquality.md)
    Mesh m;
    Frame frame;
    {
      auto ph = tool.phase("read");
      m = tool.read_mesh(in, opt);
      if (!frame_path.empty()) frame = read_frame(frame_path);
    }
    QualityReport r;
    {
      auto ph = tool.phase("measure");
      r = measure_quality(m, frame_path.empty() ? nullptr : &frame, frame_path);
    }
    tool.report()["mesh"] = in;
    tool.report().update(to_json(r));
  });
}
