#include "mesh/jitter.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "core/error.hpp"
#include "mesh/boundary.hpp"
#include "mesh/label.hpp"

namespace quadapt {

namespace {
/// A double in [0, 1) from the top 53 bits of one draw (platform-independent, unlike
/// std::uniform_real_distribution).
double unit(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

double cross(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x() - a.x()) * (c.y() - b.y()) - (b.y() - a.y()) * (c.x() - b.x());
}
}  // namespace

int jitter_interior_nodes(Mesh& m, const JitterOptions& opt, const std::string& file) {
  if (m.is_curved()) throw InputError(file, "--jitter moves the nodes of straight-sided meshes only (this one is curved)");
  if (!(opt.fraction > 0.0 && opt.fraction <= 0.45))
    throw InputError(file, "jitter fraction " + std::to_string(opt.fraction) + " is outside (0, 0.45]");
  const int n = m.num_nodes();
  // a node on an edge of one cell only (boundary, or a hanging node's half-edges) stays
  const std::vector<char> fixed = boundary_node_flags(m);
  std::vector<double> shortest(n, std::numeric_limits<double>::infinity());
  for (const Cell& c : m.cells)
    for (int e = 0; e < c.nv; ++e) {
      const int a = c.v[e], b = c.v[(e + 1) % c.nv];
      const double len = (m.nodes[a] - m.nodes[b]).norm();
      shortest[a] = std::min(shortest[a], len);
      shortest[b] = std::min(shortest[b], len);
    }
  std::mt19937_64 rng(opt.seed);
  int moved = 0;
  std::vector<Vec2> x = m.nodes;
  for (int i = 0; i < n; ++i) {
    if (fixed[i] || !std::isfinite(shortest[i])) continue;
    const double angle = 2.0 * M_PI * unit(rng);
    const double r = opt.fraction * shortest[i] * std::sqrt(unit(rng));
    x[i] += r * Vec2(std::cos(angle), std::sin(angle));
    ++moved;
  }
  for (int c = 0; c < m.num_cells(); ++c) {
    const Cell& cell = m.cells[c];
    for (int k = 0; k < cell.nv; ++k)
      if (cross(x[cell.v[k]], x[cell.v[(k + 1) % cell.nv]], x[cell.v[(k + 2) % cell.nv]]) <= 0.0)
        throw InputError(file, "jitter " + std::to_string(opt.fraction) + " makes " + cell_label(m, c) +
                                   " inverted or non-convex; use a smaller jitter");
  }
  m.nodes = std::move(x);
  m.clear_fields();
  return moved;
}

}  // namespace quadapt
