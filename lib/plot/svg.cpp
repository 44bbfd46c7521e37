#include "plot/svg.hpp"

#include <cmath>
#include <cstdio>

namespace quadapt::plot {

namespace {
std::string n2(double v) {
  char buf[40];
  if (!std::isfinite(v)) v = 0;
  std::snprintf(buf, sizeof buf, "%.2f", v);
  // trim trailing zeros: 12.50 -> 12.5, 3.00 -> 3
  std::string s = buf;
  auto dot = s.find('.');
  if (dot != std::string::npos) {
    while (!s.empty() && s.back() == '0') s.pop_back();
    if (!s.empty() && s.back() == '.') s.pop_back();
  }
  if (s == "-0") s = "0";
  return s;
}
}  // namespace

std::string svg_escape(const std::string& s) {
  std::string r;
  r.reserve(s.size());
  for (char c : s) {
    switch (c) {
      case '&': r += "&amp;"; break;
      case '<': r += "&lt;"; break;
      case '>': r += "&gt;"; break;
      case '"': r += "&quot;"; break;
      case '\'': r += "&apos;"; break;
      default: r += c;
    }
  }
  return r;
}

void PathData::num(double v) { d_ += n2(v); }

void PathData::move(double x, double y) {
  d_ += 'M';
  num(x);
  d_ += ' ';
  num(y);
}

void PathData::line(double x, double y) {
  d_ += 'L';
  num(x);
  d_ += ' ';
  num(y);
}

Svg::Svg(double width, double height) : w_(width), h_(height) {}

void Svg::rect(double x, double y, double w, double h, const std::string& fill, const std::string& stroke,
               double stroke_width) {
  body_ << "<rect x=\"" << n2(x) << "\" y=\"" << n2(y) << "\" width=\"" << n2(w) << "\" height=\"" << n2(h)
        << "\" fill=\"" << fill << "\"";
  if (stroke != "none") body_ << " stroke=\"" << stroke << "\" stroke-width=\"" << n2(stroke_width) << "\"";
  body_ << "/>\n";
}

void Svg::line(double x1, double y1, double x2, double y2, const std::string& stroke, double stroke_width) {
  body_ << "<line x1=\"" << n2(x1) << "\" y1=\"" << n2(y1) << "\" x2=\"" << n2(x2) << "\" y2=\"" << n2(y2)
        << "\" stroke=\"" << stroke << "\" stroke-width=\"" << n2(stroke_width) << "\"/>\n";
}

void Svg::polygon(const std::vector<double>& xy, const std::string& fill, const std::string& stroke,
                  double stroke_width) {
  body_ << "<polygon points=\"";
  for (size_t i = 0; i + 1 < xy.size(); i += 2) body_ << (i ? " " : "") << n2(xy[i]) << ',' << n2(xy[i + 1]);
  body_ << "\" fill=\"" << fill << "\"";
  if (stroke != "none") body_ << " stroke=\"" << stroke << "\" stroke-width=\"" << n2(stroke_width) << "\"";
  body_ << "/>\n";
}

void Svg::path(const PathData& d, const std::string& fill, const std::string& stroke, double stroke_width,
               const std::string& extra) {
  if (d.empty()) return;
  body_ << "<path d=\"" << d.str() << "\" fill=\"" << fill << "\" stroke=\"" << stroke << "\"";
  if (stroke != "none") body_ << " stroke-width=\"" << n2(stroke_width) << "\"";
  if (!extra.empty()) body_ << ' ' << extra;
  body_ << "/>\n";
}

void Svg::text(double x, double y, const std::string& s, double size, const std::string& anchor,
               const std::string& extra) {
  body_ << "<text x=\"" << n2(x) << "\" y=\"" << n2(y) << "\" font-size=\"" << n2(size)
        << "\" font-family=\"DejaVu Sans, Arial, sans-serif\" text-anchor=\"" << anchor << "\"";
  if (!extra.empty()) body_ << ' ' << extra;
  body_ << '>' << svg_escape(s) << "</text>\n";
}

void Svg::clip_rect(const std::string& id, double x, double y, double w, double h) {
  defs_ << "<clipPath id=\"" << svg_escape(id) << "\"><rect x=\"" << n2(x) << "\" y=\"" << n2(y)
        << "\" width=\"" << n2(w) << "\" height=\"" << n2(h) << "\"/></clipPath>\n";
}

void Svg::begin_group(const std::string& extra) {
  body_ << "<g" << (extra.empty() ? "" : " ") << extra << ">\n";
  ++open_groups_;
}

void Svg::end_group() {
  if (open_groups_ > 0) {
    body_ << "</g>\n";
    --open_groups_;
  }
}

std::string Svg::str() const {
  std::ostringstream os;
  os << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
     << "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" << n2(w_) << "\" height=\"" << n2(h_)
     << "\" viewBox=\"0 0 " << n2(w_) << ' ' << n2(h_) << "\">\n";
  std::string defs = defs_.str();
  if (!defs.empty()) os << "<defs>\n" << defs << "</defs>\n";
  os << body_.str();
  for (int i = 0; i < open_groups_; ++i) os << "</g>\n";
  os << "</svg>\n";
  return os.str();
}

}  // namespace quadapt::plot
