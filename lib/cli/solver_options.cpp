#include "cli/solver_options.hpp"

namespace quadapt {

void add_coarse_degree_option(CLI::App& app, int& q, const std::string& degree) {
  app.add_option("--coarse-degree", q,
                 "gmres-2level's coarse space: continuous Q_q on the mesh, q = this (0 = auto: min(" + degree +
                     ", 2); at most " + degree +
                     "). q = 2 keeps GMRES at ~15-30 iterations on the stretched cells of boundary layers, where "
                     "q = 1 needs 40-100 (docs/dgsolve.md, The coarse degree)")
      ->check(CLI::Range(0, 8))
      ->capture_default_str();
}

}  // namespace quadapt
