#include "cli/solver_options.hpp"

namespace quadapt {

void add_coarse_degree_option(CLI::App& app, int& q, const std::string& degree) {
  app.add_option("--coarse-degree", q,
                 "gmres-2level's coarse space: continuous Q_q on the mesh, q = this (0 = auto: min(" + degree +
                     ", 2); a larger q than " + degree + " runs as " + degree + ", with a warning). q = 2 keeps GMRES at ~15-30 iterations on the stretched cells of boundary layers, where "
                     "q = 1 needs 40-100 (docs/dgsolve.md, The coarse degree)")
      ->check(CLI::Range(0, 8))
      ->capture_default_str();
}

std::string coarse_degree_note(int requested, int system_degree, const LinearSolveInfo& info) {
  if (info.coarse_degree <= 0 || requested <= system_degree) return "";
  return "--coarse-degree " + std::to_string(requested) + " is above the degree " + std::to_string(system_degree) +
         " of the system: the coarse space used q = " + std::to_string(info.coarse_degree);
}

}  // namespace quadapt
