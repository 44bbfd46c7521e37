#pragma once
// Best of K lattice phases (beyond the thesis; issue #14, docs/quad-quality.md "The lattice's
// phase").
//
// The lattice start (lattice.hpp) fixes the lattice's translation x0 in x0 + V Z^2 by its seed;
// the minimisation keeps it (a translation costs nothing in the energy's interior), so it
// decides where each lattice row ends on a wall that is oblique to the frame. Some of those
// endings leave a row too close to, or too far from, a wall point: the recombined mesh then has
// a lone triangle (three quads around a valence-3 vertex) and a valence-5 neighbour there. On
// constant frames at 12 angles x 4 stretches, 9 seed positions each, 20 of 432 chains exceed 3 %
// irregular interior vertices, while every (angle, stretch) has at least 3 of its 9 phases that
// meet every target: the chain's quality is a lottery over the phase.
//
// The remedy: run the L_p-CVT from K phases and keep the one whose recombined mesh (the chain's
// own recombine: the metric matching with its defaults, split into four) has the fewest interior
// vertices of valence != 4; ties: the higher mean metric quality of the matched pairs, then the
// lower phase index. Phase k moves the lattice by phase_offset(k, K) lattice units along the axes
// the walls do not register; a phase whose start equals an earlier one's (both axes registered:
// walls along the frame) is not run again. Cost: up to K runs of lpcvt and of the matching.
// With T > 1 OpenMP threads the phases run T at a time, each on one thread (a run of a few
// thousand points hardly gains from a second thread; the result is the same for any T).
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "lpcvt/lpcvt.hpp"
#include "mesh/mesh.hpp"

namespace quadapt::lpcvt {

/// Offset of phase k of K (lattice units, each coordinate in [0, 1)): the rank-1 lattice
/// (k / K, frac(k a / K)), a the integer nearest K / golden ratio made coprime with K (the
/// Fibonacci lattice when K is a Fibonacci number): phase 0 is (0, 0) (the run without phases),
/// the K offsets are spread over the unit square, and each coordinate alone takes K distinct
/// values, so that K phases differ also when a wall registers one axis.
Vec2 phase_offset(int k, int K);

/// What the chain's recombine makes of a triangulation.
struct PhaseScore {
  int interior = 0;       ///< interior vertices of the all-quad mesh
  int irregular = 0;      ///< of those, valence != 4
  int unmatched = 0;      ///< triangles the metric matching left (each a valence-3 vertex)
  double quality = 0;     ///< mean metric quality of the matched pairs (metric_matching.hpp)
  /// Strictly better: fewer irregular, then higher quality (by more than 1e-12).
  bool better_than(const PhaseScore& o) const;
};

/// Recombines `tri` (triangles with the cell field Vinv, as run_lpcvt writes them) with the
/// recombine tool's defaults (metric matching, split into four) and scores the result.
PhaseScore recombine_score(const Mesh& tri);

struct PhaseRuns {
  LpcvtResult best;            ///< the kept phase's run
  int kept = 0;                ///< its index
  nlohmann::json runs;         ///< per phase: phase, irregular, interior, unmatched_triangles,
                               ///< pair_quality, evaluations, seconds; or same_start_as_earlier
};

/// run_lpcvt from phases 0..n-1 of `opt` (opt.lattice_phase is replaced), the best kept (above).
/// Throws NumericalError when a phase's triangulation is invalid. `log` gets one line per phase.
PhaseRuns run_phases(const Background& bg, const LpcvtOptions& opt, int n,
                     const std::function<void(const std::string&)>& log = {});

}  // namespace quadapt::lpcvt
