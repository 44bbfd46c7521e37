#pragma once
// The record of the PDE a solution was solved with, stored beside the solution in its .msh
// ($SolvedCase, one line of JSON; docs/file-formats.md) so that a tool that needs the same PDE
// (adjoint: the DWR's residual and adjoint are those of the primal's PDE) can refuse a
// different case instead of printing a meaningless estimate.
//
// The record holds what determines u_h: D, c, the exact solution (hence S and the boundary
// data taken from it), which boundaries are Dirichlet, and the data expressions; and the SIPG
// penalty factor the solve used, which the adjoint's fine space must share. Not the name,
// description or functional: a goal loop may solve with one file and add the functional in
// another. Expressions are compared with their blanks removed ("x + 1" = "x+1"); numbers as
// parsed (0.5 = "1/2").
#include <optional>
#include <string>
#include <vector>

#include "case/case.hpp"

namespace quadapt {

/// One line of compact JSON: {"advection":[cx,cy],"diffusion":[[D11,D12],[D21,D22]],
/// "dirichlet":"all" | [sorted names],"dirichlet_data":{name: expr},"exact":"...",
/// "neumann":{name: expr},"penalty":F} (keys sorted, expressions without blanks; F the
/// DGOptions::penalty_factor of the solve).
std::string solved_case_record(const Case& cs, double penalty_factor);

/// The PDE keys of the record in which `cs` differs from `record` (empty: the same PDE; the
/// penalty is not compared). Throws InputError(path, ...) when `record` is not such a record
/// (`path`: the file that held it).
std::vector<std::string> solved_case_differences(const std::string& record, const Case& cs, const std::string& path);

/// The penalty factor the record states (nullopt: none, e.g. another version's record). Throws
/// as solved_case_differences.
std::optional<double> solved_penalty(const std::string& record, const std::string& path);

}  // namespace quadapt
