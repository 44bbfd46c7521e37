#include "plot/meshplot.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <unordered_map>
#include <sstream>
#include <vector>

#include "core/error.hpp"
#include "fem/basis.hpp"
#include "mesh/boundary.hpp"
#include "mesh/curved.hpp"
#include "mesh/label.hpp"
#include "plot/svg.hpp"

namespace quadapt::plot {

namespace {

/// Line segments per curved edge (mesh/curved.hpp: the map sampled along the edge).
constexpr int kCurvedEdgeSamples = 8;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::vector<double> parse_numbers(const std::string& s, const std::string& what) {
  std::vector<double> v;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ',')) {
    try {
      size_t pos = 0;
      double x = std::stod(item, &pos);
      while (pos < item.size() && std::isspace(static_cast<unsigned char>(item[pos]))) ++pos;
      if (pos != item.size() || !std::isfinite(x)) throw std::invalid_argument(item);
      v.push_back(x);
    } catch (const std::exception&) {
      throw InputError(what + " '" + s + "': '" + item + "' is not a finite number");
    }
  }
  return v;
}

std::string available_fields(const Mesh& m) {
  std::string s;
  for (const auto& f : m.cell_fields) s += (s.empty() ? "" : ", ") + f.name;
  for (const auto& f : m.cell_node_fields) s += (s.empty() ? "" : ", ") + f.name;
  return s.empty() ? "none" : s;
}

bool intersects(const Mesh& m, int c, const Window& w) {
  const Cell& cell = m.cells[c];
  double xmin = 1e300, xmax = -1e300, ymin = 1e300, ymax = -1e300;
  for (int i = 0; i < cell.nv; ++i) {
    const Vec2& p = m.nodes[cell.v[i]];
    xmin = std::min(xmin, p.x());
    xmax = std::max(xmax, p.x());
    ymin = std::min(ymin, p.y());
    ymax = std::max(ymax, p.y());
  }
  return xmax >= w.x0 && xmin <= w.x1 && ymax >= w.y0 && ymin <= w.y1;
}

bool inside(const Vec2& p, const Window& w) { return p.x() >= w.x0 && p.x() <= w.x1 && p.y() >= w.y0 && p.y() <= w.y1; }

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return kNaN;
  size_t k = std::min(v.size() - 1, static_cast<size_t>(q * (v.size() - 1) + 0.5));
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return v[k];
}

// One coloured polygon in world coordinates.
struct Patch {
  std::array<Vec2, 4> p;
  int n = 4;
  double value = kNaN;
};

}  // namespace

Window parse_window(const std::string& s) {
  auto v = parse_numbers(s, "window");
  if (v.size() != 4) throw InputError("window '" + s + "': expected four numbers x0,x1,y0,y1");
  Window w{v[0], v[1], v[2], v[3]};
  if (!(w.x0 < w.x1) || !(w.y0 < w.y1)) throw InputError("window '" + s + "': need x0 < x1 and y0 < y1");
  return w;
}

std::pair<double, double> parse_range(const std::string& s) {
  auto v = parse_numbers(s, "range");
  if (v.size() != 2 || !(v[0] < v[1])) throw InputError("range '" + s + "': expected lo,hi with lo < hi");
  return {v[0], v[1]};
}

Window mesh_bounds(const Mesh& m) {
  // what is drawn: the cells' vertices and curved control points, not nodes no cell uses (a
  // Gmsh file keeps the geometry's points; one far away shrank the mesh to a corner)
  Window w{1e300, -1e300, 1e300, -1e300};
  auto add = [&](const Vec2& p) {
    w.x0 = std::min(w.x0, p.x());
    w.x1 = std::max(w.x1, p.x());
    w.y0 = std::min(w.y0, p.y());
    w.y1 = std::max(w.y1, p.y());
  };
  for (const Cell& c : m.cells)
    for (int k = 0; k < c.nv; ++k) add(m.nodes[c.v[k]]);
  for (const Vec2& p : m.curved.points) add(p);
  if (!(w.x1 >= w.x0)) return {};
  if (!(w.x1 > w.x0)) w.x1 = w.x0 + 1;
  if (!(w.y1 > w.y0)) w.y1 = w.y0 + 1;
  return w;
}

GlyphStyle parse_glyph(const std::string& s) {
  if (s == "cross") return GlyphStyle::Cross;
  if (s == "parallelogram") return GlyphStyle::Parallelogram;
  throw InputError("unknown glyph '" + s + "' (use cross or parallelogram)");
}

std::pair<Vec2, Vec2> frame_vectors(const CellField& vinv, int c, SizeConvention convention) {
  if (vinv.ncomp != 9) throw InputError("field '" + vinv.name + "' has " + std::to_string(vinv.ncomp) +
                                        " components; a frame needs 9 (row-major 3x3)");
  Eigen::Matrix2d M;
  M << vinv(c, 0), vinv(c, 1), vinv(c, 3), vinv(c, 4);
  try {
    return frame_axes(quadapt_factor(convention) * M);
  } catch (const NumericalError& e) {
    throw NumericalError("cell " + number_text(c) + ": " + e.what());
  }
}

void check_plot_field(const Mesh& m, const std::string& field, const std::string& source) {
  if (field.empty()) return;
  if (const CellField* f = m.cell_field(field)) {
    if (f->ncomp == 1) return;
    if (f->ncomp == 9) {  // a frame: every cell's M must be invertible (no glyph is made up)
      const SizeConvention convention = stated_convention(m, source);
      for (int c = 0; c < m.num_cells(); ++c) {
        try {
          frame_vectors(*f, c, convention);
        } catch (const NumericalError&) {
          throw InputError(source, "field '" + field + "': the frame matrix M = V^-1 is singular or not finite in " +
                                       cell_label(m, c));
        }
      }
      return;
    }
    throw InputError(source, "field '" + field + "' has " + std::to_string(f->ncomp) +
                                 " components; meshplot colours scalar fields and draws 9-component frames (Vinv)");
  }
  if (const CellNodeField* f = m.cell_node_field(field)) {
    if (f->ncomp == 1) return;
    throw InputError(source, "field '" + field + "' has " + std::to_string(f->ncomp) +
                                 " components per point; meshplot colours scalar fields only");
  }
  throw InputError(source, "no field '" + field + "' (available: " + available_fields(m) + ")");
}

std::string render_mesh_svg(const Mesh& m, const MeshPlotOptions& opt, MeshPlotSummary* summary) {
  if (m.num_cells() == 0) throw InputError(opt.source, "mesh has no cells to draw");
  check_plot_field(m, opt.field, opt.source);
  if (opt.width < 16 || opt.width > 20000) throw InputError("width " + std::to_string(opt.width) + " px out of range 16..20000");
  if (!(opt.glyph_scale > 0) || !std::isfinite(opt.glyph_scale)) throw InputError("glyph scale must be positive");
  if (opt.range && !(opt.range->second > opt.range->first)) throw InputError("colour range needs lo < hi");

  MeshPlotSummary S;
  const Window W = opt.window ? *opt.window : mesh_bounds(m);
  S.window = W;
  const bool clip = opt.window.has_value();

  // ---- which cells and which field
  std::vector<int> visible;
  visible.reserve(m.num_cells());
  for (int c = 0; c < m.num_cells(); ++c)
    if (!clip || intersects(m, c, W)) visible.push_back(c);
  S.cells_drawn = static_cast<int>(visible.size());

  const CellField* cf = opt.field.empty() ? nullptr : m.cell_field(opt.field);
  const CellNodeField* nf = (opt.field.empty() || cf) ? nullptr : m.cell_node_field(opt.field);
  const bool frame = cf && cf->ncomp == 9;
  const bool colours = (cf && cf->ncomp == 1) || nf;
  if (frame) S.field_kind = "frame";
  else if (cf) S.field_kind = "cell";
  else if (nf) S.field_kind = nf->degree >= 0 ? "dg" : "vertex";

  // ---- layout (pixels)
  const double k = opt.width / (W.x1 - W.x0);
  const double plot_w = opt.width, plot_h = (W.y1 - W.y0) * k;
  const double ml = 12, mr = colours ? 110 : 12, mt = opt.title.empty() ? 12 : 34, mb = 12;
  const double total_w = ml + plot_w + mr, total_h = mt + plot_h + mb;
  S.width_px = total_w;
  S.height_px = total_h;
  auto px = [&](const Vec2& p) { return ml + (p.x() - W.x0) * k; };
  auto py = [&](const Vec2& p) { return mt + (W.y1 - p.y()) * k; };

  // typical cell size in pixels -> stroke width
  std::vector<double> sizes;
  sizes.reserve(visible.size());
  for (int c : visible) sizes.push_back(std::sqrt(std::abs(cell_area(m, c))) * k);
  const double cell_px = percentile(sizes, 0.5);
  const double sw = std::clamp(cell_px / 15.0, 0.08, 1.0);

  Svg svg(total_w, total_h);
  svg.rect(0, 0, total_w, total_h, "#ffffff");
  if (!opt.title.empty()) svg.text(ml, 22, opt.title, 14);
  svg.clip_rect("plotarea", ml, mt, plot_w, plot_h);
  svg.begin_group(clip ? "clip-path=\"url(#plotarea)\"" : "");

  // ---- colours
  if (colours) {
    std::vector<Patch> patches;
    for (int c : visible) {
      const Cell& cell = m.cells[c];
      if (cf) {
        Patch pa;
        pa.n = cell.nv;
        for (int i = 0; i < cell.nv; ++i) pa.p[i] = m.nodes[cell.v[i]];
        pa.value = (*cf)(c);
        patches.push_back(pa);
        continue;
      }
      const double* u = nf->cell(c);
      const int p = nf->degree;
      if (p >= 0 && cell.is_quad() && nf->per_cell == (p + 1) * (p + 1)) {
        static thread_local std::map<int, LagrangeBasis1D> bases;
        auto it = bases.find(p);
        if (it == bases.end()) it = bases.emplace(p, LagrangeBasis1D(p)).first;
        int n = opt.subsample > 0 ? opt.subsample : std::max(2, 2 * p);
        if (opt.subsample <= 0) {
          // keep the picture below ~250k polygons
          int cap = std::max(1, static_cast<int>(std::sqrt(250000.0 / std::max<size_t>(1, visible.size()))));
          n = std::min(n, cap);
        }
        for (int j = 0; j < n; ++j)
          for (int i = 0; i < n; ++i) {
            const double a0 = -1 + 2.0 * i / n, a1 = -1 + 2.0 * (i + 1) / n;
            const double b0 = -1 + 2.0 * j / n, b1 = -1 + 2.0 * (j + 1) / n;
            Patch pa;
            pa.p = {map_to_physical(m, c, a0, b0), map_to_physical(m, c, a1, b0), map_to_physical(m, c, a1, b1),
                    map_to_physical(m, c, a0, b1)};
            pa.value = eval_tensor(it->second, u, 0.5 * (a0 + a1), 0.5 * (b0 + b1));
            patches.push_back(pa);
          }
      } else {
        double s = 0;
        for (int i = 0; i < nf->per_cell; ++i) s += u[i];
        Patch pa;
        pa.n = cell.nv;
        for (int i = 0; i < cell.nv; ++i) pa.p[i] = m.nodes[cell.v[i]];
        pa.value = s / std::max(1, nf->per_cell);
        patches.push_back(pa);
      }
    }
    // plotted values
    double dmin = std::numeric_limits<double>::infinity(), dmax = -dmin, minpos = dmin;
    for (auto& pa : patches) {
      if (opt.log10) {
        double a = std::abs(pa.value);
        if (std::isfinite(a) && a > 0) minpos = std::min(minpos, a);
      }
    }
    for (auto& pa : patches) {
      if (opt.log10) {
        double a = std::abs(pa.value);
        if (std::isfinite(a)) pa.value = std::log10(a > 0 ? a : (std::isfinite(minpos) ? minpos : 1.0));
      }
      if (std::isfinite(pa.value)) {
        dmin = std::min(dmin, pa.value);
        dmax = std::max(dmax, pa.value);
      }
    }
    if (!std::isfinite(dmin)) dmin = dmax = 0;
    S.data_min = dmin;
    S.data_max = dmax;
    double lo = dmin, hi = dmax;
    if (opt.range) {
      lo = opt.range->first;
      hi = opt.range->second;
    } else if (!(hi > lo)) {
      double d = std::max(1e-12, std::abs(lo) * 1e-6);
      lo -= d;
      hi += d;
    }
    S.vmin = lo;
    S.vmax = hi;
    // batch polygons by quantised colour (256 levels + NaN) into one path each
    constexpr int L = 256;
    std::vector<PathData> bins(L + 1);
    for (const auto& pa : patches) {
      int b = L;
      if (std::isfinite(pa.value)) {
        double t = (pa.value - lo) / (hi - lo);
        b = std::clamp(static_cast<int>(std::floor(std::clamp(t, 0.0, 1.0) * L)), 0, L - 1);
      }
      PathData& d = bins[b];
      d.move(px(pa.p[0]), py(pa.p[0]));
      for (int i = 1; i < pa.n; ++i) d.line(px(pa.p[i]), py(pa.p[i]));
      d.close();
    }
    S.polygons = static_cast<int>(patches.size());
    for (int b = 0; b <= L; ++b) {
      if (bins[b].empty()) continue;
      std::string col = b == L ? "#808080" : hex(colormap_rgb(opt.cmap, (b + 0.5) / L));
      // a hairline stroke of the same colour hides anti-aliasing seams between patches
      svg.path(bins[b], col, col, 0.35, "stroke-linejoin=\"round\"");
    }
  }

  // ---- edges
  if (opt.edges) {
    PathData d;
    for (int c : visible) {
      const Cell& cell = m.cells[c];
      d.move(px(m.nodes[cell.v[0]]), py(m.nodes[cell.v[0]]));
      for (int i = 0; i < cell.nv; ++i) {
        if (m.is_curved()) {  // curved edges: the map sampled along the edge
          const CellMap G(m, c);
          for (int k = 1; k < kCurvedEdgeSamples; ++k) {
            double xi = 0, eta = 0;
            edge_reference_point(i, static_cast<double>(k) / kCurvedEdgeSamples, xi, eta);
            const Vec2 x = G.map(xi, eta);
            d.line(px(x), py(x));
          }
        }
        if (i + 1 < cell.nv) d.line(px(m.nodes[cell.v[i + 1]]), py(m.nodes[cell.v[i + 1]]));
      }
      d.close();
    }
    if (frame) svg.path(d, "none", "#a8a8a8", sw, "stroke-linejoin=\"round\"");
    else if (colours) svg.path(d, "none", "#000000", sw, "stroke-opacity=\"0.45\" stroke-linejoin=\"round\"");
    else svg.path(d, "none", "#1a1a1a", sw, "stroke-linejoin=\"round\"");
  }
  {
    PathData d;
    std::unordered_map<std::uint64_t, std::pair<int, int>> cell_edge;  // directed edge -> (cell, local edge)
    if (m.is_curved())
      for (int c = 0; c < m.num_cells(); ++c)
        for (int i = 0; i < 4; ++i)
          cell_edge[directed_edge_key(m.cells[c].v[i], m.cells[c].v[(i + 1) % 4])] = {c, i};
    for (const auto& e : m.boundary) {
      const Vec2& a = m.nodes[e.v[0]];
      const Vec2& b = m.nodes[e.v[1]];
      auto it = cell_edge.find(directed_edge_key(e.v[0], e.v[1]));
      bool reversed = false;
      if (it == cell_edge.end()) {
        it = cell_edge.find(directed_edge_key(e.v[1], e.v[0]));
        reversed = true;
      }
      if (it != cell_edge.end()) {  // curved boundary edge
        const CellMap G(m, it->second.first);
        if (clip && (std::max(a.x(), b.x()) < W.x0 || std::min(a.x(), b.x()) > W.x1 || std::max(a.y(), b.y()) < W.y0 ||
                     std::min(a.y(), b.y()) > W.y1))
          continue;
        d.move(px(a), py(a));
        for (int k = 1; k <= kCurvedEdgeSamples; ++k) {
          double xi = 0, eta = 0, s = static_cast<double>(k) / kCurvedEdgeSamples;
          edge_reference_point(it->second.second, reversed ? 1 - s : s, xi, eta);
          const Vec2 x = G.map(xi, eta);
          d.line(px(x), py(x));
        }
        continue;
      }
      if (clip && std::max(a.x(), b.x()) < W.x0) continue;
      if (clip && std::min(a.x(), b.x()) > W.x1) continue;
      if (clip && std::max(a.y(), b.y()) < W.y0) continue;
      if (clip && std::min(a.y(), b.y()) > W.y1) continue;
      d.move(px(a), py(a));
      d.line(px(b), py(b));
    }
    svg.path(d, "none", "#000000", std::max(1.0, 2.5 * sw), "stroke-linecap=\"round\"");
  }

  // ---- frame glyphs
  if (frame) {
    struct G {
      Vec2 c, v, w;
      int cell;
    };
    std::vector<G> gl;
    const SizeConvention convention = stated_convention(m, opt.source);
    for (int c : visible) {
      Vec2 ctr = cell_centroid(m, c);
      if (!inside(ctr, W)) continue;
      auto [v, w] = frame_vectors(*cf, c, convention);
      gl.push_back({ctr, v, w, c});
    }
    S.glyphs = static_cast<int>(gl.size());
    const double gsw = std::clamp(cell_px / 12.0, 0.3, 1.2);
    if (opt.glyph == GlyphStyle::Cross) {
      // Sized by the cell, not by M: the longer arm is 0.45 sqrt(|K|) (times glyph_scale), the
      // other in the ratio of 1/|v| : 1/|w| (long along the small size, thesis Fig. 6.5), so a
      // glyph is readable in coarse and fine cells alike, at every zoom.
      PathData dv, dw;
      for (const auto& g : gl) {
        const double iv = 1.0 / g.v.norm(), iw = 1.0 / g.w.norm();
        const double big = std::max(iv, iw);
        if (!(big > 0) || !std::isfinite(big)) continue;
        const double L = 0.45 * opt.glyph_scale * std::sqrt(std::abs(cell_area(m, g.cell)));
        const double lv = L * (iv / big) * iv, lw = L * (iw / big) * iw;  // along v/|v|, w/|w|
        Vec2 a = g.c - lv * g.v, b = g.c + lv * g.v;
        dv.move(px(a), py(a));
        dv.line(px(b), py(b));
        a = g.c - lw * g.w;
        b = g.c + lw * g.w;
        dw.move(px(a), py(a));
        dw.line(px(b), py(b));
      }
      svg.path(dv, "none", "#d62728", gsw, "stroke-linecap=\"round\"");
      svg.path(dw, "none", "#1f4fb4", gsw, "stroke-linecap=\"round\"");
    } else {
      PathData d;
      const double s = opt.glyph_scale;
      for (const auto& g : gl) {
        const Vec2 v = s * g.v, w = s * g.w;
        const Vec2 q[4] = {g.c + v + w, g.c - v + w, g.c - v - w, g.c + v - w};
        d.move(px(q[0]), py(q[0]));
        for (int i = 1; i < 4; ++i) d.line(px(q[i]), py(q[i]));
        d.close();
      }
      svg.path(d, "none", "#c01818", gsw, "stroke-linejoin=\"round\"");
    }
  }
  svg.end_group();

  // frame around a close-up
  if (clip) svg.rect(ml, mt, plot_w, plot_h, "none", "#000000", 1.0);

  // ---- colour bar
  if (colours) {
    const double bx = ml + plot_w + 18, bw = 18, by = mt, bh = plot_h;
    const int bands = 128;
    for (int i = 0; i < bands; ++i) {
      const double t0 = static_cast<double>(i) / bands;
      svg.rect(bx, by + bh * (1 - (i + 1.0) / bands), bw, bh / bands + 0.6,
               hex(colormap_rgb(opt.cmap, t0 + 0.5 / bands)));
    }
    svg.rect(bx, by, bw, bh, "none", "#000000", 0.8);
    for (double t : nice_ticks(S.vmin, S.vmax, 5)) {
      const double y = by + bh * (1 - (t - S.vmin) / (S.vmax - S.vmin));
      svg.line(bx + bw, y, bx + bw + 4, y, "#000000", 0.8);
      svg.text(bx + bw + 7, y + 4, tick_label(t), 11);
    }
    const std::string label = opt.log10 ? "log10 |" + opt.field + "|" : opt.field;
    const double lx = bx + bw + 62, ly = by + bh / 2;
    std::ostringstream rot;
    rot << "transform=\"rotate(-90 " << lx << ' ' << ly << ")\"";
    svg.text(lx, ly, label, 12, "middle", rot.str());
  }

  if (summary) *summary = S;
  return svg.str();
}

}  // namespace quadapt::plot
