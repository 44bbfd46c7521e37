#pragma once
// Multilevel start of the L_p-CVT (beyond the thesis: fewer iterations and split/merge cycles,
// fewer lattice defects than a random start).
//
// Level l meshes the metric 2^-l M_eff (a quarter of the points per level). The coarsest level
// starts from random points drawn from the metric's density and runs the usual cycles; every
// finer level starts from the children of the previous level's free sites: a site x whose
// Voronoi cell is (at the optimum) the unit square of the coarse metric, x + V_c [-1/2, 1/2]^2
// with V_c = M_c^-1, is replaced by the centres of its four quarters,
//     x + (1/2) V_f (+-e1 +- e2),   V_f = M_f^-1 = V_c / 2,
// the optimal lattice of the finer metric wherever the coarse one was optimal (V_f evaluated at
// x). The count is then set exactly (split_merge.hpp, adjust_count) and the finer level
// minimised: it starts close to its optimum, and a lattice defect of the coarse level stays one
// defect instead of becoming four.
#include <vector>

#include "lpcvt/background.hpp"

namespace quadapt::lpcvt {

/// The children (above) of `coarse` (free sites of the coarser level) in the finer metric `fine`;
/// children outside the domain are dropped.
std::vector<Vec2> refine_sites(const Background& fine, const std::vector<Vec2>& coarse);

}  // namespace quadapt::lpcvt
