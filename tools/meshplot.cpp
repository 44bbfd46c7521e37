// meshplot: pictures of a mesh, a field as colours (DG solution, log10 DWR) or the frame as
// glyphs (thesis Fig. 6.5). Library: lib/plot/meshplot.hpp. Docs: docs/meshplot.md.
#include <cmath>

#include "cli/tool.hpp"
#include "io/msh.hpp"
#include "mesh/validate.hpp"
#include "plot/meshplot.hpp"
#include "plot/picture.hpp"

using namespace quadapt;

int main(int argc, char** argv) {
  Tool tool("meshplot", "Draw a mesh, a field as colours or the frame as glyphs (SVG or PNG)",
            "Draws the cell edges of FILE.msh (boundary thicker). --field NAME colours a scalar per-cell\n"
            "field (theta, rho, B, h, dwr, ...) or the DG solution u (sub-sampled inside each quad so the\n"
            "degree-p polynomial shows), with a colour bar; --log10 colours log10|value| (DWR). --field Vinv\n"
            "draws the frame V = M^-1 (M = upper-left 2x2 of the row-major 3x3 Vinv) as one glyph per\n"
            "cell: crosses with half-arms proportional to 1/h along v (red) and w (blue) as in thesis\n"
            "Fig. 6.5, or the target parallelograms c +- v +- w at true size (--glyph parallelogram).\n"
            "--window x0,x1,y0,y1 draws a close-up. The format follows the extension: .svg is written\n"
            "directly, .png is rendered with rsvg-convert (librsvg2-bin).");
  std::string in, out, field, window, glyph = "cross", cmap, range, title;
  bool log10 = false, no_edges = false;
  int width = 800, subsample = 0;
  double glyph_scale = 1.0;
  auto& app = tool.app();
  app.add_option("FILE", in, "Mesh (.msh) with the field to draw")->required()->check(CLI::ExistingFile);
  app.add_option("-o,--output", out, "Picture: .svg or .png")->required();
  app.add_option("--field", field, "Field to draw: a scalar cell field, the DG solution u, or the frame Vinv");
  app.add_flag("--log10", log10, "Colour log10|value| (e.g. the DWR)");
  app.add_option("--window", window, "Close-up x0,x1,y0,y1 (world coordinates)");
  app.add_option("--glyph", glyph, "Frame glyph: cross (1/h, thesis Fig. 6.5) or parallelogram (true size)")
      ->capture_default_str();
  app.add_option("--glyph-scale", glyph_scale, "Multiplies the glyph size")->capture_default_str();
  app.add_option("--width", width, "Width of the plot area in pixels")->capture_default_str();
  app.add_option("--cmap", cmap, "Colour map: viridis (default), coolwarm (default for u), gray");
  app.add_option("--range", range, "Colour range lo,hi (in log10 units with --log10)");
  app.add_option("--subsample", subsample, "DG field: sub-quads per direction in each cell (0 = auto)")
      ->capture_default_str();
  app.add_flag("--no-edges", no_edges, "Do not draw the cell edges");
  app.add_option("--title", title, "Title above the picture (default: the file and field names; '' for none)");
  tool.allow_empty_value("--title");

  return tool.run(argc, argv, [&] {
    tool.input(in);
    // the report: PICTURE.json with the extension kept (sol.png.json; default_report_path)
    tool.output(out);
    plot::picture_format(out);  // unknown extension -> error before any work
    plot::MeshPlotOptions opt;
    opt.source = in;
    opt.field = field;
    opt.log10 = log10;
    opt.width = width;
    opt.glyph = plot::parse_glyph(glyph);
    opt.glyph_scale = glyph_scale;
    opt.edges = !no_edges;
    opt.subsample = subsample;
    if (!window.empty()) opt.window = plot::parse_window(window);
    if (!range.empty()) opt.range = plot::parse_range(range);
    if (plot::picture_format(out) == plot::PictureFormat::Png && !plot::png_available())
      throw ExternalError(out + ": cannot write PNG: rsvg-convert not found (install librsvg2-bin) — or write .svg");
    Mesh m;
    {
      auto ph = tool.phase("read");
      ValidateOptions v;
      v.allow_curved = true;  // curved edges drawn by sampling the map; fills use the vertex view
      m = tool.read_mesh(in, v);
    }
    plot::check_plot_field(m, field, in);
    // colour options need colours: without a field, or with a frame (glyphs), they were ignored
    // (exit 0, the same picture; a new-user review)
    const CellField* cf = field.empty() ? nullptr : m.cell_field(field);
    if (field.empty() || (cf && cf->ncomp == 9))
      for (const char* o : {"--log10", "--range", "--cmap"})
        if (app.count(o))
          throw InputError("", std::string(o) + " colours a scalar field or the DG solution; " +
                                   (field.empty() ? "give --field NAME" : "--field " + field + " is a frame, drawn as glyphs"));
    const bool is_dg = !field.empty() && !m.cell_field(field) && m.cell_node_field(field);
    opt.cmap = plot::parse_colormap(cmap.empty() ? (is_dg ? "coolwarm" : "viridis") : cmap);
    if (app.count("--title")) opt.title = title;
    else {
      std::string base = in.substr(in.find_last_of('/') + 1);
      opt.title = base + (field.empty() ? "" : "  [" + std::string(log10 ? "log10 " : "") + field + "]") + "  " +
                  std::to_string(m.num_cells()) + " cells" + (window.empty() ? "" : ", window " + window);
    }
    plot::MeshPlotSummary s;
    std::string svg;
    {
      auto ph = tool.phase("render");
      svg = plot::render_mesh_svg(m, opt, &s);
    }
    {
      auto ph = tool.phase("write");
      plot::write_picture(svg, out);
    }
    auto& r = tool.report();
    r["cells"] = m.num_cells();
    r["cells_drawn"] = s.cells_drawn;
    r["field"] = field;
    r["field_kind"] = s.field_kind;
    r["polygons"] = s.polygons;
    r["glyphs"] = s.glyphs;
    if (s.field_kind != "none" && s.field_kind != "frame") {
      r["colour_range"] = {s.vmin, s.vmax};
      r["data_range"] = {s.data_min, s.data_max};
    }
    r["window"] = {s.window.x0, s.window.x1, s.window.y0, s.window.y1};
    r["picture_px"] = {s.width_px, s.height_px};
    if (s.cells_drawn == 0 && !window.empty())
      tool.warn("--window " + window + " holds none of " + in + "'s cells: " + out + " is empty");
    tool.log("wrote " + out + " (" + std::to_string(s.cells_drawn) + " cells)");
  });
}
