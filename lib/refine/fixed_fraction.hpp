#pragma once
// Fixed-fraction flagging (thesis §2.5): sort the cells by a per-cell indicator and flag the
// largest share F of them. F = 0.3 roughly doubles the DOFs per step (each flagged quad becomes
// four). Indicators: the largest (p+1)-th directional derivative A1, or the error constant B,
// from estimate-frame (feature-based cases); the DWR 'dwr' from adjoint (goal-oriented cases).
#include <string>
#include <vector>

#include "mesh/mesh.hpp"

namespace quadapt {

/// Number of cells flagged for a fraction F of N cells: ceil(F N) (up to rounding: F N is
/// rounded up only when it exceeds an integer by more than 1e-9), at least 1, at most N.
int fraction_count(double fraction, int num_cells);

/// Flags (#cells, 1 = split) the fraction_count(F, N) cells with the largest indicator values.
/// Ties are broken by the lower cell index, so the result is deterministic. Throws InputError
/// when F is outside (0, 1] or a value is not finite.
std::vector<char> flag_largest_fraction(const std::vector<double>& indicator, double fraction);

/// The per-cell indicator stored in m as the CellField `name` ($ElementData). Throws
/// InputError("PATH: ...") when the field is missing (listing the scalar cell fields that exist;
/// a cell-node field of that name is named as such), has more than one component, does not have
/// one value per cell, or holds a non-finite value.
std::vector<double> cell_indicator(const Mesh& m, const std::string& name, const std::string& path);

}  // namespace quadapt
