#pragma once
// Pictures of a mesh and its fields (the library behind the `meshplot` tool; docs/meshplot.md).
//
// What is drawn, in this order:
//  1. a field as colours, when MeshPlotOptions::field names
//     - a scalar CellField ($ElementData, 1 component: theta, rho, B, h, dwr, A1, ...): one
//       colour per cell;
//     - the DG solution, a CellNodeField of degree p on quads (index i + (p+1) j at the GLL
//       points, mesh/fields.hpp): each quad is sub-sampled into n x n sub-quads (n = 2p by
//       default, at least 2) coloured by the DG polynomial at the sub-quad centre
//       (fem/basis.hpp eval_tensor), so the high-order field shows inside each cell;
//     - a CellNodeField of vertex values (degree -1): the mean per cell;
//     optionally as log10 |value| (the DWR, thesis Fig. 6.21), with a colour bar;
//  2. the mesh edges (and the boundary edges thicker);
//  3. the frame, when the field is the 9-component CellField "Vinv" (docs/design.md §3:
//     M = upper-left 2x2 of the row-major 3x3, V = M^-1, columns of V are the frame vectors
//     v, w with |v| = h1, |w| = h2, eq. 3.11/3.13), as one glyph per cell centroid:
//     - Cross (default, thesis Fig. 6.5): the two axes +-v/|v| and +-w/|w| with half-lengths
//       in the ratio 1/|v| : 1/|w| (long arm along the small size), v in red, w in blue, sized
//       by the cell: the longer half-arm is 0.45 sqrt(|K|) times glyph_scale, so glyphs are
//       readable in coarse and fine cells alike;
//     - Parallelogram: the target element c +- v +- w at true size (edges 2 h1 x 2 h2,
//       eq. 5.1) times glyph_scale.
// A window (x0, x1, y0, y1) restricts the picture to a close-up (cells outside are skipped,
// the rest clipped). World y points up; the picture keeps the aspect ratio.
#include <optional>
#include <string>
#include <utility>

#include "frame/frame.hpp"
#include "mesh/mesh.hpp"
#include "plot/colormap.hpp"

namespace quadapt::plot {

/// A rectangle of the (x, y) plane.
struct Window {
  double x0 = 0, x1 = 1, y0 = 0, y1 = 1;
};

/// Parses "x0,x1,y0,y1" (x0 < x1, y0 < y1, finite). Throws InputError otherwise.
Window parse_window(const std::string& s);
/// Parses a colour range "lo,hi" (finite, lo < hi). Throws InputError otherwise.
std::pair<double, double> parse_range(const std::string& s);
/// Bounding box of what is drawn: the cells' vertices and curved control points (nodes that no
/// cell uses are left out).
Window mesh_bounds(const Mesh& m);

enum class GlyphStyle { Cross, Parallelogram };
/// "cross" | "parallelogram"; throws InputError otherwise.
GlyphStyle parse_glyph(const std::string& s);

struct MeshPlotOptions {
  std::string field;                    ///< "" = edges only
  bool log10 = false;                   ///< colour log10 |value| (zeros: the smallest positive)
  std::optional<Window> window;         ///< close-up; default = the mesh's bounding box
  int width = 800;                      ///< width of the plot area in pixels
  GlyphStyle glyph = GlyphStyle::Cross;
  double glyph_scale = 1.0;
  std::optional<std::pair<double, double>> range;  ///< colour range in plotted units (log10 units with log10)
  Colormap cmap = Colormap::Viridis;
  bool edges = true;                    ///< draw the cell edges
  int subsample = 0;                    ///< DG sub-quads per direction; 0 = auto (2p, >= 2, capped)
  std::string title;                    ///< "" = no title
  std::string source;                   ///< file name used in error messages
};

/// What render_mesh_svg drew (for the tool's JSON report and for tests).
struct MeshPlotSummary {
  std::string field_kind = "none";      ///< none | cell | dg | vertex | frame
  int cells_drawn = 0;
  int polygons = 0;                     ///< coloured polygons (sub-quads for a DG field)
  int glyphs = 0;
  double vmin = 0, vmax = 0;            ///< colour range used (plotted units)
  double data_min = 0, data_max = 0;    ///< range of the plotted values over the drawn cells
  Window window;
  double width_px = 0, height_px = 0;
};

/// Frame vectors (v, w) of cell c: the half-axes, columns of V = M^-1, M the upper-left 2x2 of
/// the 9-component row-major Vinv in the given size convention (frame/frame.hpp; meshplot uses
/// the one the file states). Throws NumericalError when M is singular or not finite.
std::pair<Vec2, Vec2> frame_vectors(const CellField& vinv, int c, SizeConvention convention = SizeConvention::Quadapt);

/// Checks that `field` can be plotted on m (exists, scalar / DG / Vinv; a 9-component frame
/// invertible in every cell). Throws InputError("SOURCE: field 'X' ...") listing the available
/// fields, or naming the first cell (1-based) whose frame is singular or not finite.
void check_plot_field(const Mesh& m, const std::string& field, const std::string& source);

/// The picture as an SVG document.
std::string render_mesh_svg(const Mesh& m, const MeshPlotOptions& opt, MeshPlotSummary* summary = nullptr);

}  // namespace quadapt::plot
