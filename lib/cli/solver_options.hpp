#pragma once
// Command-line options shared by the tools that solve DG systems (dgsolve, adjoint).
#include <CLI/CLI.hpp>
#include <string>

#include "dg/linear_solver.hpp"

namespace quadapt {

/// --coarse-degree into `q` (LinearSolverOptions::coarse_degree: 0 = auto, min(degree, 2)), in
/// [0, 8]. `degree` names the DG degree of the system the coarse space serves in the help text
/// ("P" for dgsolve, "the adjoint degree P+1").
void add_coarse_degree_option(CLI::App& app, int& q, const std::string& degree);

/// "" or a warning for the tool to give: --coarse-degree `requested` is above the degree
/// `system_degree` of the DG system the coarse space serves, so gmres-2level ran with q = that
/// degree (info.coarse_degree; a continuous Q_q is a subspace of the DG space only for q <= p).
std::string coarse_degree_note(int requested, int system_degree, const LinearSolveInfo& info);

}  // namespace quadapt
