#pragma once
// Initial interior points of the L_p-CVT (thesis Algorithm 3, "distribute volume nodes").
//
// Uniform: cells drawn with probability proportional to their area (the thesis's random start,
// §6.1 uses 20 such points). Density: proportional to area * |det M_eff|, the point density the
// metric asks for, so that the split/merge cycles have little left to do. Within a cell the
// point is uniform (a quad is split into two triangles, chosen by area). Deterministic for a
// given seed (std::mt19937).
#include <vector>

#include "lpcvt/background.hpp"

namespace quadapt::lpcvt {

/// Uniform and Density: random (below). Lattice: the frame-aligned lattice (lattice.hpp), made
/// by run_lpcvt (seed_points treats it as Density).
enum class SeedMode { Uniform, Density, Lattice };

/// n points strictly inside the domain.
std::vector<Vec2> seed_points(const Background& bg, int n, SeedMode mode, unsigned seed);

}  // namespace quadapt::lpcvt
