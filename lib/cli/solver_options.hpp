#pragma once
// Command-line options shared by the tools that solve DG systems (dgsolve, adjoint).
#include <CLI/CLI.hpp>
#include <string>

namespace quadapt {

/// --coarse-degree into `q` (LinearSolverOptions::coarse_degree: 0 = auto, min(degree, 2)), in
/// [0, 8]. `degree` names the DG degree of the system the coarse space serves in the help text
/// ("P" for dgsolve, "the adjoint degree P+1").
void add_coarse_degree_option(CLI::App& app, int& q, const std::string& degree);

}  // namespace quadapt
