#pragma once
// The DG degrees quadapt supports: one range for the library, the tools and the loop.
// dgsolve takes p in kMinDegree..kMaxDegree; adjoint works on the degree p+1 space, so it takes
// solutions of degree up to kMaxDegree - 1. dgsolve's --help states the range as "(1..8)", which
// is where the loop (scripts/loop/run-loop.sh) reads it from.
#include <string>

#include "core/error.hpp"

namespace quadapt {

constexpr int kMinDegree = 1;
constexpr int kMaxDegree = 8;
constexpr int kMaxAdjointDegree = kMaxDegree - 1;

/// "1..8"
inline std::string degree_range_text(int max = kMaxDegree) {
  return std::to_string(kMinDegree) + ".." + std::to_string(max);
}

/// Throws InputError("WHAT p is out of range (1..MAX)") unless kMinDegree <= p <= max.
inline void check_degree(int p, const std::string& what = "degree", int max = kMaxDegree) {
  if (p < kMinDegree || p > max)
    throw InputError(what + " " + std::to_string(p) + " is out of range (" + degree_range_text(max) + ")");
}

}  // namespace quadapt
