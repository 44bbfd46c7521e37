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

}  // namespace quadapt
