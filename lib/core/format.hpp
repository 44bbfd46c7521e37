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

/// A count that may be fractional (a frame's target cells): whole from 100 on ("1012"), else three
/// significant digits ("0.0025", "12.5") — a frame asking 0.0025 cells printed as "0".
inline std::string count_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, v >= 100 || v <= -100 ? "%.0f" : "%.3g", v);
  return buf;
}

/// A point (x, y) as "(x, y)" with both coordinates as sci() prints them: "(5.000e-01, 1.000e+00)".
inline std::string sci_point(double x, double y) { return "(" + sci(x) + ", " + sci(y) + ")"; }

}  // namespace quadapt
