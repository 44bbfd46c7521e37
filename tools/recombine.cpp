// recombine: triangles -> all-quad mesh (thesis §4.6): Blossom-Quad through the Gmsh SDK, then
// each quad split into 4 and each remaining triangle into 3. See docs/recombine.md.
#include <string>

#include "cli/frame_coverage.hpp"
#include "cli/parse_errors.hpp"
#include "cli/tool.hpp"
#include "core/format.hpp"
#include "io/msh.hpp"
#include "mesh/validate.hpp"
#include "quad/recombine.hpp"
#include "quad/report.hpp"
#include "frame/frame.hpp"

int main(int argc, char** argv) {
  using namespace quadapt;
  Tool tool("recombine", "Triangles paired into quads (metric matching or Blossom-Quad), then split to all-quad",
            "Reads a triangle mesh (e.g. from lpcvt) and pairs its triangles into quads. Default when "
            "a frame is known (TRI's cell field Vinv, as lpcvt writes it, or --frame FRAME.msh): a "
            "maximum-weight matching whose weight is each pair's quad quality in the frame's metric "
            "(1 - max |corner angle - 90 deg| / 90 deg; pairs at or below --min-quality are never "
            "made; the matching need not be perfect, so a lattice defect stays a lone triangle "
            "instead of a chain of sheared pairs; docs/recombine.md). Otherwise (or --matching "
            "blossom) Gmsh's Blossom-Quad (minimum-cost perfect matching in physical space; "
            "Mesh.RecombinationAlgorithm = 1). For Blossom an odd "
            "triangle count is first made even by splitting the boundary triangle with the longest "
            "boundary edge, so that Blossom does not fall back to greedy matching. Then every quad "
            "is split into 4 and every remaining triangle into 3 (exact edge midpoints and cell "
            "centres), which halves the edge lengths: generate the triangles with twice the final "
            "edge length. Boundary nodes never move; the boundary groups (names and tags) are "
            "carried through. Orientation, area and boundary are checked after Gmsh. Report: "
            "triangles in, quads/triangles after Blossom, cells out, quality (angles, scaled "
            "Jacobian), and whether Gmsh's clean-up failed its checks (fell_back).");
  std::string in, out;
  RecombineOptions opt;
  auto& app = tool.app();
  app.add_option("TRI", in, "Input triangle mesh (.msh) with boundary groups")->required()->check(CLI::ExistingFile);
  app.add_option("-o,--output", out, "Output all-quad mesh (.msh); report beside it as .json")->required();
  bool pairing = false;
  app.add_flag("--pairing", pairing,
               "Blossom-Quad (--matching blossom) only: use Blossom's matching alone, every quad is two "
               "input triangles, no node moves or disappears (Blossom's default: Gmsh's topological "
               "clean-up and node relocation, checked, with the pairing as fall-back)");
  app.add_option("--topology-passes", opt.blossom.optimize_topology,
                 "Blossom-Quad only: Gmsh's topological optimisation passes (Mesh.RecombineOptimizeTopology)")
      ->capture_default_str()
      ->check(NonNegativeValue);
  app.add_option("--relocation-passes", opt.blossom.smoothing,
                 "Blossom-Quad only: Gmsh's node relocation passes after recombination (Mesh.Smoothing)")
      ->capture_default_str()
      ->check(NonNegativeValue);
  std::string matching, frame_path;
  app.add_option("--matching", matching,
                 "metric (default when a frame is known) or blossom (Gmsh; the default without a frame)")
      ->check(CLI::IsMember({"metric", "blossom"}));
  app.add_option("--frame", frame_path,
                 "Frame file (background mesh with the cell field Vinv) for the metric matching, when TRI "
                 "carries no Vinv field")
      ->check(CLI::ExistingFile);
  app.add_option("--min-quality", opt.metric.min_quality,
                 "Metric matching: pairs of metric quality at or below this stay triangles")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 0.99));
  app.add_option("--pair-bonus", opt.metric.pair_bonus,
                 "Metric matching: weight added to every pair (larger: fewer unmatched triangles, longer "
                 "chains of sheared pairs)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 10.0));
  app.add_option("--interior-bonus", opt.metric.interior_bonus,
                 "Metric matching: weight added per paired triangle without a boundary edge, so that a "
                 "lattice defect's lone triangle is left at the wall, not one row inside it (0 = off; "
                 "docs/recombine.md)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 10.0));
  bool no_split = false;
  app.add_flag("--no-split", no_split, "Stop after Blossom: write the quad-dominant mesh");

  return tool.run(argc, argv, [&] {
    tool.input(in);
    tool.output_mesh(out);
    opt.split = !no_split;
    opt.blossom.gmsh_cleanup = !pairing;
    tool.option("split", opt.split);
    Mesh tri;
    {
      auto ph = tool.phase("read");
      tri = tool.read_mesh(in, ValidateOptions::cells(CellKind::Triangles));
      const bool has_frame = !frame_path.empty() || tri.cell_field("Vinv");
      if (matching.empty()) matching = has_frame ? "metric" : "blossom";
      if (matching == "metric") {
        // Blossom's options do nothing here: refused, as the metric ones are under Blossom (they
        // were ignored, the report naming a mode that never ran: a docs audit)
        for (const char* o : {"--pairing", "--topology-passes", "--relocation-passes"})
          if (app.count(o))
            throw InputError("", std::string(o) + " applies to Blossom-Quad only (--matching blossom); the metric "
                                                  "matching, the default with a frame, keeps every node and has no clean-up");
        if (!frame_path.empty()) {
          tool.input(frame_path);
          opt.with_frame(sample_frame_checked(tool, read_frame(frame_path), tri, in, frame_path));
        } else if (tri.cell_field("Vinv")) {
          opt.with_frame(frame_from_mesh(tri, in).oriented());
        } else {
          throw InputError(in, "--matching metric needs a frame: a cell field Vinv in TRI or --frame FRAME.msh");
        }
      } else {
        for (const char* o : {"--min-quality", "--pair-bonus", "--interior-bonus"})
          if (app.count(o))
            throw InputError("", std::string(o) + " applies to the metric matching only: give a frame (TRI's "
                                                  "cell field Vinv or --frame FRAME.msh), not --matching blossom");
      }
    }
    tool.option("matching", matching);
    if (matching == "blossom") {  // Blossom's own options: only where they act
      tool.option("mode", pairing ? "pairing" : "gmsh-cleanup");
      tool.option("topology_passes", opt.blossom.optimize_topology);
      tool.option("relocation_passes", opt.blossom.smoothing);
      for (const char* k : {"min_quality", "pair_bonus", "interior_bonus"}) tool.report()["options"].erase(k);
    } else {
      tool.report()["options"].erase("pairing");
      tool.report()["options"].erase("topology_passes");
      tool.report()["options"].erase("relocation_passes");
    }
    if (matching == "metric") tool.option("min_quality", opt.metric.min_quality);
    RecombineStats st;
    Mesh q;
    {
      auto ph = tool.phase("recombine");
      q = recombine_to_all_quads(tri, opt, &st, in);
    }
    auto rep = to_json(st);
    for (auto it = rep.begin(); it != rep.end(); ++it) tool.report()[it.key()] = it.value();
    const bool metric = opt.matching == RecombineOptions::Matching::Metric;
    tool.log(std::to_string(st.triangles_in) + " triangles -> " +
             std::to_string(metric ? st.metric.quads : st.blossom.quads) + " quads + " +
             std::to_string(metric ? st.metric.triangles : st.blossom.triangles) + " triangles -> " + std::to_string(st.cells_out) +
             " cells; min angle " + sci(st.quality.min_angle_deg) + " deg, min scaled Jacobian " +
             sci(st.quality.min_scaled_jacobian));
    {
      auto ph = tool.phase("write");
      write_msh(q, out);
    }
  });
}
