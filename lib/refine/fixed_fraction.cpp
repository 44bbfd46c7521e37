#include "refine/fixed_fraction.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

#include "core/error.hpp"
#include "mesh/label.hpp"

namespace quadapt {

namespace {
std::string num(double x) {
  std::ostringstream os;
  os << x;
  return os.str();
}
}  // namespace

int fraction_count(double fraction, int num_cells) {
  if (!(fraction > 0.0 && fraction <= 1.0))
    throw InputError("", "fraction " + num(fraction) + " is outside (0, 1]");
  const double x = fraction * num_cells;
  int n = static_cast<int>(std::ceil(x - 1e-9));
  return std::clamp(n, std::min(1, num_cells), num_cells);
}

std::vector<char> flag_largest_fraction(const std::vector<double>& indicator, double fraction) {
  const int n = static_cast<int>(indicator.size());
  const int k = fraction_count(fraction, n);
  for (int c = 0; c < n; ++c)
    if (!std::isfinite(indicator[c]))
      throw InputError("", "indicator of cell " + number_text(c) + " is " + num(indicator[c]));
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  auto larger = [&](int a, int b) {
    return indicator[a] != indicator[b] ? indicator[a] > indicator[b] : a < b;
  };
  std::partial_sort(order.begin(), order.begin() + k, order.end(), larger);
  std::vector<char> flags(n, 0);
  for (int i = 0; i < k; ++i) flags[order[i]] = 1;
  return flags;
}

std::vector<double> cell_indicator(const Mesh& m, const std::string& name, const std::string& path) {
  const CellField* f = m.cell_field(name);
  if (!f) {
    std::string have;
    for (const auto& g : m.cell_fields) have += (have.empty() ? "" : ", ") + g.name;
    std::string msg = "no cell field '" + name + "' ($ElementData)";
    if (m.cell_node_field(name)) msg += " ('" + name + "' is a per-node field, not one value per cell)";
    msg += "; cell fields present: " + (have.empty() ? std::string("none") : have);
    throw InputError(path, msg);
  }
  if (f->ncomp != 1)
    throw InputError(path, "field '" + name + "' has " + std::to_string(f->ncomp) +
                               " components; the indicator must be a scalar (1 component)");
  if (f->values.size() != m.cells.size())
    throw InputError(path, "field '" + name + "' has " + std::to_string(f->values.size()) +
                               " values for " + std::to_string(m.num_cells()) + " cells");
  for (int c = 0; c < m.num_cells(); ++c)
    if (!std::isfinite(f->values[c]))
      throw InputError(path, "field '" + name + "' is " + num(f->values[c]) + " in " + cell_label(m, c));
  return f->values;
}

}  // namespace quadapt
