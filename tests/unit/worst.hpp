#pragma once
// A running maximum of an error measure that keeps NaN: std::max(worst, NaN) returns worst (every
// comparison with NaN is false), so a NaN result — a gradient, a field, a coordinate gone bad —
// would score as no error at all and pass CHECK(worst < tol). worst_of(worst, e) is NaN as soon
// as either is, and the CHECK then fails.
#include <cmath>
#include <limits>

namespace quadapt_test {

inline double worst_of(double worst, double e) {
  if (std::isnan(worst) || std::isnan(e)) return std::numeric_limits<double>::quiet_NaN();
  return e > worst ? e : worst;
}

}  // namespace quadapt_test
