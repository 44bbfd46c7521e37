#pragma once
// A minimal SVG 1.1 writer for quadapt's pictures (meshplot). Coordinates are pixels with the
// origin at the top-left corner and y pointing down (SVG's convention); the caller maps world
// coordinates. Numbers are printed with 2 decimals (1/100 px), which keeps files of 10^5 cells
// at a few MB. Nothing here touches the file system; see plot/picture.hpp for writing.
#include <sstream>
#include <string>
#include <vector>

namespace quadapt::plot {

/// Escapes &, <, >, " and ' for use in SVG text and attribute values.
std::string svg_escape(const std::string& s);

/// Builds the "d" attribute of an SVG path: move/line/close commands in pixels.
class PathData {
 public:
  void move(double x, double y);
  void line(double x, double y);
  void close() { d_ += 'Z'; }
  bool empty() const { return d_.empty(); }
  const std::string& str() const { return d_; }

 private:
  void num(double v);
  std::string d_;
};

/// An SVG document of width x height pixels, built element by element.
class Svg {
 public:
  Svg(double width, double height);
  double width() const { return w_; }
  double height() const { return h_; }

  /// <rect>; fill/stroke are SVG paint strings ("#rrggbb", "none").
  void rect(double x, double y, double w, double h, const std::string& fill,
            const std::string& stroke = "none", double stroke_width = 0);
  /// <line>.
  void line(double x1, double y1, double x2, double y2, const std::string& stroke, double stroke_width);
  /// Closed polygon from pixel points (x0, y0, x1, y1, ...).
  void polygon(const std::vector<double>& xy, const std::string& fill, const std::string& stroke = "none",
               double stroke_width = 0);
  /// <path d="..."> with fill/stroke; `extra` is appended verbatim inside the tag
  /// (e.g. "stroke-opacity=\"0.5\"").
  void path(const PathData& d, const std::string& fill, const std::string& stroke, double stroke_width,
            const std::string& extra = "");
  /// <text>; anchor = "start" | "middle" | "end". The string is escaped.
  void text(double x, double y, const std::string& s, double size, const std::string& anchor = "start",
            const std::string& extra = "");
  /// A clip rectangle usable as clip-path="url(#id)".
  void clip_rect(const std::string& id, double x, double y, double w, double h);
  /// <g extra>... </g>.
  void begin_group(const std::string& extra = "");
  void end_group();

  /// The complete document.
  std::string str() const;

 private:
  double w_, h_;
  std::ostringstream body_;
  std::ostringstream defs_;
  int open_groups_ = 0;
};

}  // namespace quadapt::plot
