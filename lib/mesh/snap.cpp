#include "mesh/snap.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "core/error.hpp"
#include "core/format.hpp"
#include "mesh/boundary.hpp"

namespace quadapt {

std::vector<std::vector<int>> group_curves(const Mesh& m, const BoundaryGeometry& g, const std::string& path) {
  std::vector<std::vector<int>> r(m.groups.size());
  std::vector<char> used(m.groups.size(), 0);
  for (const auto& e : m.boundary) used.at(e.group) = 1;
  for (size_t k = 0; k < m.groups.size(); ++k) {
    r[k] = g.curves_named(m.groups[k].name);
    if (r[k].empty() && used[k]) {
      std::string names;
      for (const auto& n : g.names()) names += (names.empty() ? "" : ", ") + n;
      throw InputError(path, "boundary '" + m.groups[k].name + "' is not a physical curve of " + g.source() +
                                 " (its curves: " + names + ")");
    }
  }
  return r;
}

double wendland_c2(double r) { return r >= 1 ? 0.0 : std::pow(1 - r, 4) * (4 * r + 1); }

namespace {

enum class Interior { Stay, Parent, Blend };

SnapStats snap_once(Mesh& m, const BoundaryGeometry& g, const std::string& path, Interior interior) {
  if (m.is_curved()) throw Error("snap_to_geometry: the mesh is curved");
  if (m.boundary.empty()) complete_boundary(m);
  const auto curves = group_curves(m, g, path);
  std::map<int, std::vector<int>> node_curves;  // node -> candidate curves
  std::map<int, double> node_edge;              // node -> shortest boundary edge at it
  std::map<int, int> node_group;                // node -> a boundary group of it (the first edge's)
  for (const auto& e : m.boundary) {
    const double len = (m.nodes[e.v[0]] - m.nodes[e.v[1]]).norm();
    for (int v : e.v) {
      node_group.emplace(v, e.group);
      auto& cs = node_curves[v];
      for (int k : curves[e.group])
        if (std::find(cs.begin(), cs.end(), k) == cs.end()) cs.push_back(k);
      auto it = node_edge.find(v);
      node_edge[v] = it == node_edge.end() ? len : std::min(it->second, len);
    }
  }
  SnapStats s;
  const std::vector<Vec2> before = m.nodes;
  // per group: nodes already on its curves, nodes, the largest move relative to the edge at the node
  std::vector<int> group_on(m.groups.size(), 0), group_nodes(m.groups.size(), 0);
  std::vector<double> group_rel(m.groups.size(), 0), group_move(m.groups.size(), 0);
  for (auto& [v, cs] : node_curves) {
    ++s.boundary_nodes;
    int k = -1;
    Vec2 p = g.closest_point(cs, m.nodes[v], &k);
    const double d = (p - m.nodes[v]).norm();
    if (d > 0.5 * node_edge[v])
      throw InputError(path, "boundary node " + number_text(v) + " at " + point_text(m.nodes[v]) + " is " +
                                 sci(d) + " from curve '" + g.curves()[k].name + "' of " + g.source() +
                                 ": the mesh is not a mesh of that geometry");
    if (d > 0) ++s.moved;
    s.max_move = std::max(s.max_move, d);
    const int grp = node_group[v];
    ++group_nodes[grp];
    if (d <= 1e-9 * node_edge[v]) ++group_on[grp];
    if (d / node_edge[v] > group_rel[grp]) {
      group_rel[grp] = d / node_edge[v];
      group_move[grp] = d;
    }
    m.nodes[v] = p;
  }
  for (size_t grp = 0; grp < m.groups.size(); ++grp)
    if (group_nodes[grp] >= 3 && group_on[grp] == 0 && group_rel[grp] > 0.05)
      s.warnings.push_back("none of the " + std::to_string(group_nodes[grp]) + " nodes of boundary '" + m.groups[grp].name +
                           "' lay on its curves of " + g.source() + " (moved by up to " + sci(group_move[grp]) + ", " +
                           std::to_string(static_cast<int>(std::lround(100 * group_rel[grp]))) +
                           " % of the shortest boundary edge there): is the mesh one of that geometry's domain?");
  if (interior == Interior::Parent) {
    // a split parent's centre C follows its Coons map: the children of a quad (triangle) parent
    // around a mid-edge node M share M and C, and C (valence 4, resp. 3) moves by 1/2 (2/3) of M's move
    std::vector<std::vector<int>> cells_of(m.nodes.size());
    for (int c = 0; c < m.num_cells(); ++c)
      for (int i = 0; i < m.cells[c].nv; ++i) cells_of[m.cells[c].v[i]].push_back(c);
    std::vector<Vec2> D(m.nodes.size(), Vec2(0, 0));
    for (auto& [v, cs] : node_curves) {
      const Vec2 d = m.nodes[v] - before[v];
      if (d.isZero(0) || cells_of[v].size() != 2) continue;
      const Cell &a = m.cells[cells_of[v][0]], &b = m.cells[cells_of[v][1]];
      int centre = -1, shared = 0;
      for (int i = 0; i < a.nv; ++i)
        for (int j = 0; j < b.nv; ++j)
          if (a.v[i] == b.v[j] && a.v[i] != v && !node_curves.count(a.v[i])) {
            centre = a.v[i];
            ++shared;
          }
      if (shared != 1) continue;
      const size_t val = cells_of[centre].size();
      if (val == 4) D[centre] += 0.5 * d;
      else if (val == 3) D[centre] += (2.0 / 3.0) * d;
    }
    for (size_t v = 0; v < D.size(); ++v)
      if (!D[v].isZero(0)) {
        m.nodes[v] = before[v] + D[v];
        s.max_interior_move = std::max(s.max_interior_move, D[v].norm());
      }
  }
  if (interior == Interior::Blend) {
    struct Move {
      Vec2 x, d;
      double rho;
    };
    std::vector<Move> moves;
    for (auto& [v, cs] : node_curves)
      if (m.nodes[v] != before[v]) moves.push_back({before[v], m.nodes[v] - before[v], node_edge[v]});
    for (int v = 0; v < m.num_nodes() && !moves.empty(); ++v) {
      if (node_curves.count(v)) continue;
      Vec2 D(0, 0);
      double W = 0;
      for (const auto& mv : moves) {
        const Vec2 r = before[v] - mv.x;
        if (std::abs(r.x()) >= mv.rho || std::abs(r.y()) >= mv.rho) continue;
        const double w = wendland_c2(r.norm() / mv.rho);
        D += w * mv.d;
        W += w;
      }
      if (W > 1) D /= W;
      m.nodes[v] = before[v] + D;
      s.max_interior_move = std::max(s.max_interior_move, D.norm());
    }
  }
  for (auto& [v, cs] : node_curves) {
    Vec2 p = g.closest_point(cs, m.nodes[v]);
    s.max_distance = std::max(s.max_distance, (p - m.nodes[v]).norm());
  }
  // a moved node must not invert a cell: every corner that turned left (det J >
  // 0 of the bilinear map there) still does
  auto turn = [&](const std::vector<Vec2>& x, const Cell& cell, int i) {
    const Vec2 &a = x[cell.v[(i + cell.nv - 1) % cell.nv]], &b = x[cell.v[i]], &d = x[cell.v[(i + 1) % cell.nv]];
    const Vec2 u = b - a, w = d - b;
    return u.x() * w.y() - u.y() * w.x();
  };
  for (int c = 0; c < m.num_cells(); ++c) {
    const Cell& cell = m.cells[c];
    bool touched = false;
    for (int i = 0; i < cell.nv; ++i) touched |= m.nodes[cell.v[i]] != before[cell.v[i]];
    if (!touched) continue;
    for (int i = 0; i < cell.nv; ++i)
      if (turn(before, cell, i) > 0 && turn(m.nodes, cell, i) <= 0)
        throw NumericalError(path + ": snapping the boundary to " + g.source() + " inverts cell " + number_text(c) +
                             " at " + point_text(before[cell.v[i]]) +
                             " (the cell is thinner than the curve's deviation from its chord)");
  }
  return s;
}

}  // namespace

SnapStats snap_to_geometry(Mesh& m, const BoundaryGeometry& g, const std::string& path, bool move_interior) {
  if (move_interior)  // split parents' centres follow; else only the boundary moves; else the blend
    for (Interior mode : {Interior::Parent, Interior::Stay}) {
      Mesh copy = m;
      try {
        SnapStats s = snap_once(copy, g, path, mode);
        m = std::move(copy);
        return s;
      } catch (const NumericalError&) {
      }
    }
  return snap_once(m, g, path, move_interior ? Interior::Blend : Interior::Stay);
}

}  // namespace quadapt
