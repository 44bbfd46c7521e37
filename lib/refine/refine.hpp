#pragma once
// The refine baselines (thesis §2.5, docs/design.md §1): uniform refinement (every quad into 4) and
// fixed-fraction refinement (the share F of cells with the largest indicator split into 4, then
// extra splits so that face neighbours differ by at most one level, thesis Fig. 2.2), hanging
// nodes kept. Input: an all-quad mesh, conforming or 2:1 non-conforming (e.g. a previous
// output). Output: the refined mesh with the boundary groups carried to the children and no
// fields (optionally the scalar cell fields copied to the children, refine/split.hpp).
// Coarsening is not implemented (files carry no refinement history).
#include <string>

#include "mesh/mesh.hpp"

namespace quadapt {

struct RefineOptions {
  enum class Mode { Uniform, Fraction };
  Mode mode = Mode::Uniform;
  double fraction = 0.3;      ///< Fraction mode: share F in (0, 1] of cells flagged
  std::string by;             ///< Fraction mode: name of the 1-component CellField indicator
  bool keep_scalar_fields = false;  ///< copy 1-component CellFields to the children
};

struct RefineStats {
  int cells_before = 0, cells_after = 0;
  int nodes_before = 0, nodes_after = 0;
  int flagged = 0;            ///< cells flagged by the indicator (uniform: all)
  int added_by_balance = 0;   ///< extra cells split to keep the 2:1 rule
  int split = 0;              ///< flagged + added_by_balance
  int hanging_before = 0, hanging_after = 0;  ///< hanging nodes (coarse edges) before / after
};

/// Refines m. `path` names the input in error messages. Throws InputError("PATH: ...") for a
/// mesh that is not all-quad, a non-conformity other than 2:1, F outside (0, 1], or a missing /
/// multi-component / wrong-length / non-finite indicator field.
Mesh refine_mesh(const Mesh& m, const RefineOptions& opt, RefineStats* stats = nullptr,
                 const std::string& path = "mesh");

}  // namespace quadapt
