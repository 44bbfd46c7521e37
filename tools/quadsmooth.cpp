// quadsmooth: angle-based smoothing (Zhou & Shimada, thesis §4.6 ref. [135]) of a quad mesh,
// never lowering the minimum angle, never inverting a cell. See docs/quadsmooth.md.
#include <memory>
#include <string>
#include <vector>

#include "cli/frame_coverage.hpp"
#include "cli/parse_errors.hpp"
#include "cli/tool.hpp"
#include "core/format.hpp"
#include "io/msh.hpp"
#include "mesh/validate.hpp"
#include "quad/quality_summary.hpp"
#include "quad/report.hpp"
#include "quad/frame_smooth.hpp"
#include "quad/smooth.hpp"
#include "frame/frame.hpp"
#include "lpcvt/fit_frame.hpp"
#include "quality/mesh_quality.hpp"

int main(int argc, char** argv) {
  using namespace quadapt;
  Tool tool("quadsmooth", "Smoothing of interior nodes: angle-based (Zhou & Shimada) or a fit to the frame's squares (wall nodes slide along straight walls)",
            "Moves each interior node to the average of its positions that would make the segment "
            "to each edge neighbour bisect the angle between the two cells at that neighbour "
            "(Zhou & Shimada 2000, the smoothing of thesis §4.6). A move that would invert a cell or "
            "lower the smallest angle of the cells around the node is halved (--halvings times) "
            "and otherwise skipped, so the mesh's minimum angle never decreases and no cell "
            "inverts. Boundary and hanging nodes stay fixed (the shape fit slides wall nodes along "
            "straight walls, --walls). Gauss-Seidel sweeps in node order "
            "(deterministic). Input: a conforming quad (or mixed) mesh without inverted cells; "
            "output: the same connectivity and boundary groups, new interior node positions, "
            "no fields. With --frame FRAME.msh (cell field Vinv, M = V^-1) the angles are measured "
            "in the frame's metric space (each node's star mapped by M at the node), which keeps "
            "the sizes of a mesh made for that frame (boundary layers). "
            "--method shape (the default with --frame) fits every corner, mapped by the frame's "
            "metric, to a square of the frame's size instead (a local/global least-squares fit: "
            "right angles AND target edge lengths; no minimum-angle guarantee, only no inverted "
            "cell; docs/quadsmooth.md); its sweeps go colour by colour (no two nodes of a colour "
            "share a cell) and move a colour's nodes in parallel, so the mesh is the same for any "
            "--threads. "
            "Report: sweeps and the rule that stopped them (stop: tolerance or the sweeps cap), moves accepted/reduced/rejected, quality before/after.");
  std::string in, out, frame_path, method;
  SmoothOptions opt;
  ShapeSmoothOptions shape;
  int sweeps = -1;
  auto& app = tool.app();
  app.add_option("QUAD", in, "Input quad mesh (.msh)")->required()->check(CLI::ExistingFile);
  app.add_option("-o,--output", out, "Output mesh (.msh); report beside it as .json")->required();
  app.add_option("--sweeps", sweeps,
                 "Smoothing sweeps over the interior nodes (default: 3 for angle, at most 30 for shape)")
      ->check(NonNegativeValue);
  app.add_option("--method", method,
                 "angle (Zhou & Shimada; the default without --frame) or shape (corner fit to the frame's "
                 "squares; the default with --frame, needs it)")
      ->check(CLI::IsMember({"angle", "shape"}));
  app.add_option("--halvings", opt.max_halvings, "Halvings of a rejected move before it is skipped")
      ->capture_default_str()
      ->check(NonNegativeValue);
  app.add_option("--relaxation", shape.relaxation,
                 "Shape fit: over-relaxation of each interior node's step (1 = plain Gauss-Seidel; in (0, 2); "
                 "docs/quadsmooth.md, \"Over-relaxation\")")
      ->capture_default_str();  // range: lib/cli/option_ranges.cpp
  double tolerance = -1;
  app.add_option("--tolerance", tolerance,
                 "Stop when no node moves more than this fraction of its mean edge length (default: 0 "
                 "for angle, 1e-3 for shape)")
      ->check(NonNegativeValue);
  std::string corner_metric = "node";
  app.add_option("--corner-metric", corner_metric,
                 "Shape fit: the metric of each corner, at its own node (node) or the cell's at its centroid "
                 "(cell: all corners of a quad in one metric, as meshquality --frame measures it)")
      ->capture_default_str()->check(CLI::IsMember({"node", "cell"}));
  std::string walls = "slide";
  app.add_option("--walls", walls,
                 "Shape fit: wall nodes slide along their wall where it is straight, between their two wall "
                 "neighbours (slide: the lattice's rows may meet an oblique wall square in the metric "
                 "instead of shearing the mesh; corners, ends of boundary groups and nodes of curved walls "
                 "stay) or every boundary node stays (fixed). docs/quadsmooth.md, \"Walls\"")
      ->capture_default_str()->check(CLI::IsMember({"slide", "fixed"}));
  std::string fit = "raw";
  lpcvt::FitFrameOptions fit_opt;
  app.add_option("--fit-frame", fit,
                 "Shape fit: the frame it aims at — raw (FRAME as read), meshed (the filtered frame lpcvt meshes, "
                 "as lpcvt --write-frame) or capped (meshed, but never coarser than FRAME along any direction, "
                 "rescaled to meshed's cell count). "
                 "docs/quadsmooth.md, \"Which frame the fit aims at\"")
      ->capture_default_str()->check(CLI::IsMember({"raw", "meshed", "capped"}));
  app.add_option("--frame-smooth", fit_opt.smooth,
                 "Shape fit, --fit-frame meshed/capped: log-Euclidean smoothing passes of the filter (lpcvt --smooth)")
      ->capture_default_str()->check(CLI::Range(0, 1000));
  app.add_option("--frame-gradation", fit_opt.gradation,
                 "Shape fit, --fit-frame meshed/capped: size gradation of the filter, growth per unit metric "
                 "length (lpcvt --gradation; 0 = none)")
      ->capture_default_str();  // range: lib/cli/option_ranges.cpp (0 or > 1, checked before reading)
  app.add_option("--frame", frame_path,
                 "Frame file (background mesh with the cell field Vinv): smooth in its metric space")
      ->check(CLI::ExistingFile);

  return tool.run(argc, argv, [&] {
    tool.input(in);
    tool.output_mesh(out);
    if (method.empty()) method = frame_path.empty() ? "angle" : "shape";
    if (method == "shape" && frame_path.empty())
      throw InputError("", "--method shape needs --frame FRAME.msh (the squares are the frame's)");
    if (sweeps >= 0) opt.sweeps = shape.sweeps = sweeps;
    if (tolerance >= 0) opt.tolerance = shape.tolerance = tolerance;
    shape.max_halvings = opt.max_halvings;
    if (method != "shape" && tool.app().count("--corner-metric"))
      throw InputError("", "--corner-metric applies to the shape fit only (--method shape with --frame)");
    shape.cell_metric = corner_metric == "cell";
    if (method != "shape" && tool.app().count("--walls"))
      throw InputError("", "--walls applies to the shape fit only (--method shape with --frame)");
    shape.slide_walls = walls == "slide";
    for (const char* o : {"--fit-frame", "--frame-smooth", "--frame-gradation"})
      if (method != "shape" && tool.app().count(o))
        throw InputError("", std::string(o) + " applies to the shape fit only (--method shape with --frame)");
    fit_opt.mode = lpcvt::parse_fit_frame(fit, in);
    if (method != "shape" && tool.app().count("--relaxation"))
      throw InputError("", "--relaxation applies to the shape fit only (--method shape with --frame)");
    if (method == "shape") {
      tool.option("relaxation", shape.relaxation);
      tool.option("corner_metric", corner_metric);
      tool.option("walls", walls);
      tool.option("fit_frame", fit);
      if (fit_opt.mode != lpcvt::FitFrame::Raw) {
        tool.option("frame_smooth", fit_opt.smooth);
        tool.option("frame_gradation", fit_opt.gradation);
      }
    }
    tool.option("method", method);
    tool.option("sweeps", method == "shape" ? shape.sweeps : opt.sweeps);
    tool.option("halvings", opt.max_halvings);
    tool.option("tolerance", method == "shape" ? shape.tolerance : opt.tolerance);
    if (!frame_path.empty()) tool.input(frame_path);
    tool.option("space", frame_path.empty() ? "physical" : "metric");
    Mesh m;
    Frame frame;
    {
      auto ph = tool.phase("read");
      m = tool.read_mesh(in);
      if (!frame_path.empty()) frame = read_frame(frame_path);
    }
    if (!frame_path.empty()) {
      // a frame that does not cover the mesh (another run's, another domain's) is sampled at its
      // nearest cell there: said, not silent (a reviewer's L-shape frame on a [0,2]x[0,1] mesh)
      sample_frame_checked(tool, frame, m, in, frame_path);
    }
    if (method == "shape" && fit_opt.mode != lpcvt::FitFrame::Raw) {
      auto ph = tool.phase("fit_frame");
      lpcvt::FitFrameReport fr;
      frame = lpcvt::fit_frame(frame, fit_opt, &fr);
      tool.report()["fit_frame"] = {{"mode", fit}, {"smoothed_cells", fr.smoothed_cells}, {"graded_cells", fr.graded_cells},
                                    {"capped_cells", fr.capped_cells}, {"cap_rescale", fr.cap_rescale}};
      tool.log(std::string("fit frame ") + fit + ": " + std::to_string(fr.smoothed_cells) + " cells smoothed, " +
               std::to_string(fr.graded_cells) + " graded" +
               (fit_opt.mode == lpcvt::FitFrame::Capped
                    ? ", " + std::to_string(fr.capped_cells) + " capped at FRAME's size (rescale " + sci(fr.cap_rescale) + ")"
                    : std::string()));
    }
    const QualitySummary before = quality_summary(m);
    if (before.inverted > 0)
      throw InputError(in, std::to_string(before.inverted) + " cells are inverted or non-convex (scaled Jacobian <= 0)");
    SmoothStats st;
    {
      auto ph = tool.phase("smooth");
      m.clear_fields();
      if (method == "shape") {  // needs --frame (checked above)
        st = shape_smooth_to_frame(m, frame, shape);
      } else {
        NodeMetric metric;
        std::unique_ptr<FrameSampler> sampler;
        if (!frame_path.empty()) {
          sampler = std::make_unique<FrameSampler>(frame);  // reflections removed: det M > 0
          metric = [&](const Vec2& x) { return sampler->at(x); };
        }
        st = angle_smooth(m, opt, metric);
      }
    }
    const QualitySummary after = quality_summary(m);
    auto& rep = tool.report();
    rep["cells"] = m.num_cells();
    rep["interior_nodes"] = st.interior_nodes;
    if (method == "shape") rep["sliding_wall_nodes"] = st.sliding_nodes;
    rep["sweeps"] = st.sweeps;
    // which rule ended the sweeps: the tolerance (converged) or the sweeps cap (docs/quadsmooth.md,
    // "How far the sweeps converge": the shape fit almost always stops on the cap)
    rep["stop"] = st.converged ? "tolerance" : "sweeps";
    rep["moves_full"] = st.moves_full;
    rep["moves_reduced"] = st.moves_reduced;
    rep["moves_rejected"] = st.moves_rejected;
    rep["max_displacement"] = st.max_displacement;
    rep["quality_before"] = to_json(before);
    rep["quality"] = to_json(after);
    tool.log(std::to_string(st.sweeps) +
             (st.converged ? " sweeps (converged)" : " sweeps (the cap; not converged to the tolerance)") +
             " over " + std::to_string(st.interior_nodes) +
             " interior nodes" + (st.sliding_nodes ? " and " + std::to_string(st.sliding_nodes) + " wall nodes" : "") +
             "; min angle " + sci(before.min_angle_deg) + " -> " +
             sci(after.min_angle_deg) + " deg, mean cell min angle " +
             sci(before.mean_cell_min_angle_deg) + " -> " + sci(after.mean_cell_min_angle_deg));
    {
      auto ph = tool.phase("write");
      write_msh(m, out);
    }
  });
}
