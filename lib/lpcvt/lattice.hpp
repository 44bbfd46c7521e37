#pragma once
// Frame-aligned lattice start of the L_p-CVT (beyond the thesis, which starts from random
// points): a breadth-first growth of the lattice the frame describes.
//
// At the optimum of the L_p-CVT energy for a constant metric the sites form the lattice
// x0 + V_eff Z^2 (V_eff = M_eff^-1, unit metric spacing along the frame's axes, the Voronoi cells
// the frame's parallelograms). The growth starts from a seed and, for every accepted
// point p, proposes its four lattice neighbours p +- V(p) e1, p +- V(p) e2 (V at p, so the lattice
// follows the frame as it turns and grades). A proposal y is accepted when it lies inside the
// domain and no point (the fixed boundary points included) is within metric distance `delta` of
// it, |M_eff(y) (q - y)|_2 < delta (found by a range search on an incremental Delaunay
// triangulation of the accepted points: a breadth-first walk from the nearest point over the
// points within the Euclidean radius delta * |V(y)|_2). Proposals are processed ring by ring
// from the seed (ring = lattice steps from it), within a ring nearest the seed first (Euclidean
// distance), then in the order they were made: where the frame grades, two parents propose
// nearly the same point and the first taken wins, and ring and distance turn and mirror with
// the problem, where the order of the four proposals (+a, +b, -a, -b along V's columns, whose
// signs a mirrored frame's canonical V flips) does not — the first-in, first-out queue this
// replaces grew a mirrored PHiLiP frame's lattice otherwise (55-264 start points differed;
// tests/cli/graded_equivariance.sh). Deterministic. Seeds: the
// centroids of the background cells, finest metric (largest |det M|) first; a seed is used when
// no point is within one metric unit of it once the growth from the previous seeds has stopped,
// so the finest region sets the lattice and every region the growth cannot reach gets its own.
// delta = 0.75 rejects the centre of a lattice square (distance 0.71) and accepts the lattice
// neighbours (1) with some slack where the frame grades.
//
// Where the frame is constant the result is the optimal lattice itself, aligned with the frame:
// the minimisation only has to relax the defect lines where the frame turns or jumps and the
// rows meeting the boundary, and the rows cannot settle at a wrong spacing (random starts often
// freeze with rows 1.3 units apart, which halves the output's stretch).
#include <vector>

#include "lpcvt/background.hpp"

namespace quadapt::lpcvt {

/// The seed y moved by less than one lattice cell so that the lattice y + M^-1 Z^2 is in phase
/// with the fixed points within metric distance `radius` of y, per lattice axis, where those are
/// in phase with each other (circular mean of frac(M (b - y)) with resultant length > 0.5);
/// along an axis where they are not (a boundary oblique to the frame) moved by phase[axis]
/// lattice units instead (0: unchanged). `registered` (optional, 2 entries) says which axes the
/// fixed points set.
Vec2 register_seed(const Vec2& y, const Mat2& M, const std::vector<Vec2>& fixed, double radius,
                   const Vec2& phase = Vec2::Zero(), bool* registered = nullptr);

/// The interior points grown (above) given the fixed points `fixed`; at most `max_points`.
/// `phase` (lattice units, each in [0, 1)): every seed moved by M^-1 phase along the axes that the
/// wall does not register (register_seed) — the lattice's translation against oblique walls,
/// which the minimisation keeps and which decides where rows end on the walls (lpcvt/phases.hpp).
std::vector<Vec2> lattice_points(const Background& bg, const std::vector<Vec2>& fixed,
                                 double delta = 0.75, int max_points = 10000000,
                                 const Vec2& phase = Vec2::Zero());

}  // namespace quadapt::lpcvt
