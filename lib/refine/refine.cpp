#include "refine/refine.hpp"

#include <sstream>
#include <vector>

#include "core/error.hpp"
#include "mesh/topology.hpp"
#include "refine/balance.hpp"
#include "refine/cell_edges.hpp"
#include "refine/fixed_fraction.hpp"
#include "refine/split.hpp"

namespace quadapt {

Mesh refine_mesh(const Mesh& m, const RefineOptions& opt, RefineStats* stats, const std::string& path) {
  if (m.cells.empty()) throw InputError(path, "the mesh has no cells");
  if (!m.all_quads())
    throw InputError(path, "refine needs an all-quad mesh; found " + std::to_string(m.num_triangles()) +
                               " triangles");
  std::vector<char> flags;
  if (opt.mode == RefineOptions::Mode::Uniform) {
    flags.assign(m.cells.size(), 1);
  } else {
    if (!(opt.fraction > 0.0 && opt.fraction <= 1.0)) {
      std::ostringstream os;
      os << "fraction " << opt.fraction << " is outside (0, 1]";
      throw InputError(path, os.str());
    }
    if (opt.by.empty()) throw InputError(path, "fixed-fraction refinement needs an indicator field (--by)");
    flags = flag_largest_fraction(cell_indicator(m, opt.by, path), opt.fraction);
  }

  Topology t;
  CellEdges edges;
  try {
    t = build_topology(m);
    edges = classify_cell_edges(m, t);
  } catch (const InputError& e) {
    // Topology errors say "mesh: ..."; name the file instead.
    std::string msg = e.what();
    if (msg.rfind("mesh: ", 0) == 0) msg = msg.substr(6);
    throw InputError(path, msg);
  }

  RefineStats s;
  s.cells_before = m.num_cells();
  s.nodes_before = m.num_nodes();
  for (char f : flags) s.flagged += f != 0;
  for (int c = 0; c < m.num_cells(); ++c)
    for (int e = 0; e < 4; ++e) s.hanging_before += edges[c][e].kind == EdgeKind::Coarse;
  s.added_by_balance = balance_flags(edges, flags);
  s.split = s.flagged + s.added_by_balance;

  Mesh out = split_cells(m, edges, flags, opt.keep_scalar_fields);
  s.cells_after = out.num_cells();
  s.nodes_after = out.num_nodes();
  s.hanging_after = count_hanging_nodes(out);
  if (stats) *stats = s;
  return out;
}

}  // namespace quadapt
