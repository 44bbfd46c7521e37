#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <cmath>
#include <sstream>
#include <string>

#include "core/error.hpp"
#include "fem/basis.hpp"
#include "mesh/mesh.hpp"
#include "plot/colormap.hpp"
#include "plot/meshplot.hpp"
#include "plot/svg.hpp"

using namespace quadapt;
using namespace quadapt::plot;

namespace {
int count(const std::string& s, const std::string& what) {
  int n = 0;
  for (size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
  return n;
}
// Frame field with V = R(theta) diag(h1, h2) in every cell, stored as Vinv = M = V^-1 (row-major 3x3).
CellField frame_field(int cells, double theta, double h1, double h2) {
  Eigen::Matrix2d R;
  R << std::cos(theta), -std::sin(theta), std::sin(theta), std::cos(theta);
  Eigen::Matrix2d V = R * Eigen::Vector2d(h1, h2).asDiagonal();
  Eigen::Matrix2d M = V.inverse();
  CellField f{"Vinv", 9, std::vector<double>(static_cast<size_t>(cells) * 9, 0.0)};
  for (int c = 0; c < cells; ++c) {
    f(c, 0) = M(0, 0);
    f(c, 1) = M(0, 1);
    f(c, 3) = M(1, 0);
    f(c, 4) = M(1, 1);
    f(c, 8) = 1;
  }
  return f;
}
}  // namespace

TEST_CASE("colour maps: viridis end points, clamping, NaN, hex") {
  CHECK(hex(colormap_rgb(Colormap::Viridis, 0.0)) == "#440154");
  CHECK(hex(colormap_rgb(Colormap::Viridis, 1.0)) == "#fde725");
  CHECK(hex(colormap_rgb(Colormap::Viridis, -3.0)) == "#440154");
  CHECK(hex(colormap_rgb(Colormap::Viridis, 7.0)) == "#fde725");
  CHECK(hex(colormap_rgb(Colormap::Gray, 0.5)) == "#808080");
  CHECK(hex(colormap_rgb(Colormap::Coolwarm, std::nan(""))) == "#808080");
  CHECK(parse_colormap("coolwarm") == Colormap::Coolwarm);
  CHECK_THROWS_AS(parse_colormap("jet"), InputError);
}

TEST_CASE("nice ticks: 1-2-5 steps inside the range") {
  auto t = nice_ticks(0, 1, 5);
  REQUIRE(t.size() == 6);
  CHECK(t[0] == 0);
  CHECK(t[5] == doctest::Approx(1.0));
  auto u = nice_ticks(-12.3, -3.7, 5);  // step 2: -12 ... -4
  CHECK(u.front() == doctest::Approx(-12));
  CHECK(u.back() == doctest::Approx(-4));
  for (double v : u) CHECK((v >= -12.3 && v <= -3.7));
  CHECK(nice_ticks(2, 2).size() == 1);
  CHECK(tick_label(-0.0) == "0");
  CHECK(tick_label(1.5e-7) == "1.5e-07");
}

TEST_CASE("svg escaping and path data") {
  CHECK(svg_escape("a<b & \"c\"") == "a&lt;b &amp; &quot;c&quot;");
  PathData d;
  d.move(1, 2.5);
  d.line(3.256, -0.001);
  d.close();
  CHECK(d.str() == "M1 2.5L3.26 0Z");
}

TEST_CASE("window and range parsing") {
  Window w = parse_window("0.2,0.4, 0.8,1");
  CHECK(w.x0 == 0.2);
  CHECK(w.y1 == 1.0);
  CHECK_THROWS_AS(parse_window("0,1,0"), InputError);
  CHECK_THROWS_AS(parse_window("1,0,0,1"), InputError);
  CHECK_THROWS_AS(parse_window("0,1,a,1"), InputError);
  CHECK_THROWS_AS(parse_window("0,1,nan,1"), InputError);
  auto r = parse_range("-3,2");
  CHECK(r.first == -3);
  CHECK_THROWS_AS(parse_range("2,2"), InputError);
  CHECK(parse_glyph("parallelogram") == GlyphStyle::Parallelogram);
  CHECK_THROWS_AS(parse_glyph("arrow"), InputError);
}

TEST_CASE("the picture's bounds: the cells and their curved edges, not nodes no cell uses") {
  Mesh m = make_structured_quads(2, 2);
  m.nodes.emplace_back(50, -20);  // a geometry point Gmsh kept (was: the mesh drawn in a corner)
  Window w = mesh_bounds(m);
  CHECK(w.x0 == 0);
  CHECK(w.x1 == 1);
  CHECK(w.y0 == 0);
  CHECK(w.y1 == 1);
  m.curved.order = 2;  // a control point bulging below y = 0 widens the box
  m.curved.points.assign(9 * m.num_cells(), Vec2(0.5, 0.5));
  m.curved.points[1] = Vec2(0.25, -0.1);
  w = mesh_bounds(m);
  CHECK(w.y0 == doctest::Approx(-0.1));
  CHECK(w.x1 == 1);
}

TEST_CASE("frame vectors are the columns of V = M^-1 (eq. 3.11, 3.13)") {
  const double theta = 0.5236, h1 = 0.01, h2 = 0.1;
  CellField f = frame_field(1, theta, h1, h2);
  auto [v, w] = frame_vectors(f, 0);
  CHECK(v.x() == doctest::Approx(h1 * std::cos(theta)));
  CHECK(v.y() == doctest::Approx(h1 * std::sin(theta)));
  CHECK(w.x() == doctest::Approx(-h2 * std::sin(theta)));
  CHECK(w.y() == doctest::Approx(h2 * std::cos(theta)));
  CellField bad{"Vinv", 9, std::vector<double>(9, 0.0)};
  CHECK_THROWS_AS(frame_vectors(bad, 0), NumericalError);
  CellField scalar{"h", 1, {1.0}};
  CHECK_THROWS_AS(frame_vectors(scalar, 0), InputError);
}

TEST_CASE("render: edges only, close-up window keeps the touching cells") {
  Mesh m = make_structured_quads(4, 4);
  MeshPlotSummary s;
  MeshPlotOptions o;
  std::string svg = render_mesh_svg(m, o, &s);
  CHECK(s.cells_drawn == 16);
  CHECK(s.field_kind == "none");
  CHECK(svg.rfind("<?xml", 0) == 0);
  CHECK(svg.find("</svg>") != std::string::npos);
  CHECK(count(svg, "<path") == 2);  // cell edges + boundary
  o.window = Window{0, 0.4, 0, 0.4};
  svg = render_mesh_svg(m, o, &s);
  CHECK(s.cells_drawn == 4);  // columns/rows 0 and 1 (x in [0,0.5] reaches 0.4)
  CHECK(svg.find("clip-path") != std::string::npos);
  CHECK(s.width_px == doctest::Approx(12 + 800 + 12));
}

TEST_CASE("render: scalar cell field, log10, colour bar") {
  Mesh m = make_structured_quads(3, 1);
  m.set_field(CellField{"dwr", 1, {1e-8, 1e-4, 0.0}});
  MeshPlotOptions o;
  o.field = "dwr";
  o.log10 = true;
  MeshPlotSummary s;
  std::string svg = render_mesh_svg(m, o, &s);
  CHECK(s.field_kind == "cell");
  CHECK(s.polygons == 3);
  CHECK(s.data_min == doctest::Approx(-8));  // zero is shown as the smallest positive value
  CHECK(s.data_max == doctest::Approx(-4));
  CHECK(svg.find("log10 |dwr|") != std::string::npos);
  o.field = "nope";
  o.source = "x.msh";
  try {
    render_mesh_svg(m, o);
    FAIL("expected an error");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("x.msh: no field 'nope' (available: dwr)") != std::string::npos);
  }
}

TEST_CASE("render: DG field is sub-sampled with the tensor GLL basis") {
  // u = x + 2 y, exact in the degree-1 basis: the sub-quad centre values span a known range.
  Mesh m = make_structured_quads(4, 4);
  const int p = 1, n = p + 1;
  LagrangeBasis1D b(p);
  CellNodeField u{"u", 1, n * n, p, {}};
  for (int c = 0; c < m.num_cells(); ++c)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        Vec2 x = map_to_physical(m, c, b.nodes()[i], b.nodes()[j]);
        u.values.push_back(x.x() + 2 * x.y());
      }
  m.set_field(u);
  MeshPlotOptions o;
  o.field = "u";
  MeshPlotSummary s;
  render_mesh_svg(m, o, &s);
  CHECK(s.field_kind == "dg");
  CHECK(s.polygons == 16 * 4);  // n = max(2, 2p) = 2 sub-quads per direction
  CHECK(s.data_min == doctest::Approx(3.0 / 16));       // centre (1/16, 1/16)
  CHECK(s.data_max == doctest::Approx(3 * 15.0 / 16));  // centre (15/16, 15/16)
  o.subsample = 3;
  render_mesh_svg(m, o, &s);
  CHECK(s.polygons == 16 * 9);
  o.range = std::make_pair(0.0, 1.0);
  render_mesh_svg(m, o, &s);
  CHECK(s.vmax == 1.0);
}

TEST_CASE("render: frame glyphs, one per cell centre in the window") {
  Mesh m = make_structured_quads(5, 5);
  m.set_field(frame_field(25, 0.3, 0.01, 0.05));
  MeshPlotOptions o;
  o.field = "Vinv";
  MeshPlotSummary s;
  std::string svg = render_mesh_svg(m, o, &s);
  CHECK(s.field_kind == "frame");
  CHECK(s.glyphs == 25);
  CHECK(count(svg, "#d62728") == 1);  // all v arms in one path
  CHECK(count(svg, "M") > 50);
  o.glyph = GlyphStyle::Parallelogram;
  o.window = Window{0, 0.45, 0, 0.45};
  render_mesh_svg(m, o, &s);
  CHECK(s.glyphs == 4);  // centres 0.1, 0.3 in each direction
}

TEST_CASE("render: cross glyphs are sized by their cell, readable where sizes span decades") {
  // Half the cells ask for h = 1e-3, the others for h = 0.1 (isotropic, axis-aligned): with
  // glyphs sized by M the coarse cells' crosses were 100x shorter than the fine ones, below a pixel.
  Mesh m = make_structured_quads(8, 8);
  CellField f = frame_field(64, 0.0, 0.1, 0.1);
  const CellField fine = frame_field(64, 0.0, 1e-3, 1e-3);
  for (int c = 0; c < 32; ++c)
    for (int k = 0; k < 9; ++k) f(c, k) = fine(c, k);
  m.set_field(f);
  MeshPlotOptions o;
  o.field = "Vinv";
  o.width = 800;
  const std::string svg = render_mesh_svg(m, o);
  // the red path: "M x y L x y" per glyph
  const size_t at = svg.find("stroke=\"#d62728\"");
  REQUIRE(at != std::string::npos);
  const size_t d0 = svg.rfind("d=\"", at) + 3, d1 = svg.find('"', d0);
  std::string d = svg.substr(d0, d1 - d0);
  for (char& ch : d)
    if (ch == 'M' || ch == 'L') ch = ' ';
  std::istringstream in(d);
  double x0, y0, x1, y1, lo = 1e300, hi = 0;
  int n = 0;
  while (in >> x0 >> y0 >> x1 >> y1) {
    const double len = std::hypot(x1 - x0, y1 - y0);
    lo = std::min(lo, len);
    hi = std::max(hi, len);
    ++n;
  }
  CHECK(n == 64);
  const double cell_px = 800.0 / 8;  // 100 px
  CHECK(lo >= 0.8 * cell_px);        // full arm = 0.9 sqrt(|K|) = 90 px in every cell
  CHECK(hi <= 1.0 * cell_px);        // and inside its cell
}
