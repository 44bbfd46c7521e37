#include "plot/colormap.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.hpp"

namespace quadapt::plot {

namespace {
// matplotlib viridis at t = 0, 0.1, ..., 1.
const double kViridis10[11][3] = {
    {0.267004, 0.004874, 0.329415}, {0.282623, 0.140926, 0.457517}, {0.253935, 0.265254, 0.529983},
    {0.206756, 0.371758, 0.553117}, {0.163625, 0.471133, 0.558148}, {0.127568, 0.566949, 0.550556},
    {0.134692, 0.658636, 0.517649}, {0.266941, 0.748751, 0.440573}, {0.477504, 0.821444, 0.318195},
    {0.741388, 0.873449, 0.149561}, {0.993248, 0.906157, 0.143936}};
// Moreland's cool-warm at t = 0, 0.25, 0.5, 0.75, 1.
const double kCoolwarm[5][3] = {{0.230, 0.299, 0.754},
                                {0.552, 0.690, 0.996},
                                {0.866, 0.866, 0.866},
                                {0.956, 0.604, 0.486},
                                {0.706, 0.016, 0.150}};

Rgb interp(const double (*table)[3], int n, double t) {
  double s = t * (n - 1);
  int i = std::min(n - 2, std::max(0, static_cast<int>(std::floor(s))));
  double f = s - i;
  return {table[i][0] + f * (table[i + 1][0] - table[i][0]), table[i][1] + f * (table[i + 1][1] - table[i][1]),
          table[i][2] + f * (table[i + 1][2] - table[i][2])};
}
}  // namespace

Colormap parse_colormap(const std::string& name) {
  if (name == "viridis") return Colormap::Viridis;
  if (name == "coolwarm") return Colormap::Coolwarm;
  if (name == "gray" || name == "grey") return Colormap::Gray;
  throw InputError("unknown colour map '" + name + "' (use viridis, coolwarm or gray)");
}

Rgb colormap_rgb(Colormap map, double t) {
  if (std::isnan(t)) return {0.5, 0.5, 0.5};
  t = std::clamp(t, 0.0, 1.0);
  switch (map) {
    case Colormap::Viridis: return interp(kViridis10, 11, t);
    case Colormap::Coolwarm: return interp(kCoolwarm, 5, t);
    case Colormap::Gray: return {t, t, t};
  }
  return {t, t, t};
}

std::string hex(const Rgb& c) {
  auto ch = [](double v) { return static_cast<int>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0)); };
  char buf[8];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", ch(c.r), ch(c.g), ch(c.b));
  return buf;
}

std::vector<double> nice_ticks(double lo, double hi, int target) {
  if (!(hi > lo)) return {lo};
  target = std::max(target, 2);
  double raw = (hi - lo) / target;
  double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * mag >= raw) {
      step = m * mag;
      break;
    }
  std::vector<double> t;
  double first = std::ceil(lo / step - 1e-9) * step;
  for (double v = first; v <= hi + 1e-9 * step; v += step) t.push_back(std::abs(v) < 1e-12 * step ? 0.0 : v);
  if (t.empty()) t.push_back(lo);
  return t;
}

std::string tick_label(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  std::string s = buf;
  if (s == "-0") s = "0";
  return s;
}

}  // namespace quadapt::plot
