#include "estimate/interpolate.hpp"

#include "core/error.hpp"
#include "fem/basis.hpp"

namespace quadapt {

CellNodeField interpolate_dg(const Mesh& m, int p, const std::function<double(double, double)>& f,
                             const std::string& name) {
  if (p < 1) throw InputError("interpolate_dg: p must be >= 1");
  if (!m.all_quads()) throw InputError("interpolate_dg: needs an all-quad mesh");
  LagrangeBasis1D b(p);
  const auto& x = b.nodes();
  const int np1 = p + 1;
  CellNodeField u;
  u.name = name;
  u.ncomp = 1;
  u.per_cell = np1 * np1;
  u.degree = p;
  u.values.resize(static_cast<size_t>(m.num_cells()) * np1 * np1);
  for (int c = 0; c < m.num_cells(); ++c)
    for (int j = 0; j < np1; ++j)
      for (int i = 0; i < np1; ++i) {
        const Vec2 X = map_to_physical(m, c, x[i], x[j]);
        u.values[static_cast<size_t>(c) * np1 * np1 + i + np1 * j] = f(X.x(), X.y());
      }
  return u;
}

}  // namespace quadapt
