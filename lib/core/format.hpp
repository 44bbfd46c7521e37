#pragma once
// How quadapt prints a floating-point value in messages and logs: "%.3e" (7.500e-08), so that
// small errors never print as 0.000000 and large bounds never print as 310 digits.
#include <cstdio>
#include <string>

namespace quadapt {

inline std::string sci(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3e", v);
  return buf;
}

/// A point (x, y) as "(x, y)" with both coordinates as sci() prints them: "(5.000e-01, 1.000e+00)".
inline std::string sci_point(double x, double y) { return "(" + sci(x) + ", " + sci(y) + ")"; }

}  // namespace quadapt
