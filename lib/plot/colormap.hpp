#pragma once
// Colour maps and axis ticks for quadapt's pictures (meshplot, docs/meshplot.md).
//
// A colour map sends t in [0, 1] (clamped; NaN -> mid grey) to an sRGB colour. "viridis" is the
// perceptually uniform default (matplotlib's, sampled at 11 anchors and interpolated linearly in
// sRGB, within a few 1/255 of the 256-entry table); "coolwarm" is a
// diverging blue-white-red map for signed fields (solutions); "gray" goes black to white.
#include <string>
#include <vector>

namespace quadapt::plot {

/// An sRGB colour, each channel in [0, 1].
struct Rgb {
  double r = 0, g = 0, b = 0;
};

enum class Colormap { Viridis, Coolwarm, Gray };

/// "viridis" | "coolwarm" | "gray"; throws InputError naming the unknown map otherwise.
Colormap parse_colormap(const std::string& name);

/// Colour of t in [0, 1] (values outside are clamped; NaN gives #808080).
Rgb colormap_rgb(Colormap map, double t);

/// "#rrggbb" (channels rounded to 0..255).
std::string hex(const Rgb& c);

/// "Nice" tick values (1, 2, 5 x 10^k steps) inside [lo, hi], about `target` of them; always
/// at least one value. lo <= hi required (equal is allowed).
std::vector<double> nice_ticks(double lo, double hi, int target = 5);

/// Short label for a tick value: "%.3g", with "-0" printed as "0".
std::string tick_label(double v);

}  // namespace quadapt::plot
