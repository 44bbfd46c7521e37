#include "mesh/topology.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <unordered_map>

#include "core/error.hpp"
#include "mesh/label.hpp"

namespace quadapt {

namespace {
using EdgeKey = std::pair<int, int>;
EdgeKey key(int a, int b) { return a < b ? EdgeKey{a, b} : EdgeKey{b, a}; }

struct HalfEdge {
  int cell, edge, from, to;
};

Face make_face(const Mesh& m, int c0, int e0, double sa0, double sb0, const Vec2& a, const Vec2& b) {
  Face f;
  f.cell = {c0, -1};
  f.local_edge = {e0, -1};
  f.s_a = {sa0, 0};
  f.s_b = {sb0, 1};
  f.a = a;
  f.b = b;
  Vec2 t = b - a;
  f.length = t.norm();
  f.normal = Vec2(t.y(), -t.x()) / f.length;  // outward for a counter-clockwise cell
  return f;
}
}  // namespace

std::vector<int> Topology::neighbours(int c) const {
  std::vector<int> out;
  for (int fi : cell_faces[c]) {
    const Face& f = faces[fi];
    int other = f.cell[0] == c ? f.cell[1] : f.cell[0];
    if (other >= 0 && std::find(out.begin(), out.end(), other) == out.end()) out.push_back(other);
  }
  return out;
}

Topology build_topology(const Mesh& m) {
  Topology t;
  t.cell_faces.assign(m.cells.size(), {});
  std::map<EdgeKey, std::vector<HalfEdge>> edges;
  for (int c = 0; c < m.num_cells(); ++c) {
    const Cell& cell = m.cells[c];
    for (int e = 0; e < cell.nv; ++e) {
      int a = cell.v[e], b = cell.v[(e + 1) % cell.nv];
      edges[key(a, b)].push_back({c, e, a, b});
    }
  }
  std::map<EdgeKey, int> bgroup;
  for (const auto& be : m.boundary) bgroup[key(be.v[0], be.v[1])] = be.group;

  auto add = [&](Face f) {
    int id = static_cast<int>(t.faces.size());
    t.cell_faces[f.cell[0]].push_back(id);
    if (f.cell[1] >= 0) t.cell_faces[f.cell[1]].push_back(id);
    t.faces.push_back(std::move(f));
  };

  // Unmatched half-edges, indexed by their vertices, for the hanging-node search.
  std::unordered_multimap<int, EdgeKey> unmatched_at;
  std::map<EdgeKey, bool> used;
  for (auto& [k, hs] : edges) {
    if (hs.size() > 2)
      throw InputError("mesh", "the edge between nodes " + number_text(k.first) + " " + point_text(m.nodes[k.first]) +
                                   " and " + number_text(k.second) + " " + point_text(m.nodes[k.second]) +
                                   " is shared by " + std::to_string(hs.size()) + " cells");
    if (hs.size() == 2) {
      const HalfEdge &h0 = hs[0], &h1 = hs[1];
      if (h0.from == h1.from)
        throw InputError("mesh", "cells " + number_text(h0.cell) + " and " + number_text(h1.cell) +
                                     " overlap or have opposite orientation");
      Face f = make_face(m, h0.cell, h0.edge, 0, 1, m.nodes[h0.from], m.nodes[h0.to]);
      f.cell[1] = h1.cell;
      f.local_edge[1] = h1.edge;
      f.s_a[1] = 1;
      f.s_b[1] = 0;
      add(std::move(f));
    } else {
      unmatched_at.emplace(k.first, k);
      unmatched_at.emplace(k.second, k);
    }
  }

  // Hanging nodes: a coarse edge (a, b) whose two halves (a, h) and (h, b) are fine edges.
  for (auto& [k, hs] : edges) {
    if (hs.size() != 1 || used[k]) continue;
    const HalfEdge& coarse = hs[0];
    const Vec2 &pa = m.nodes[coarse.from], &pb = m.nodes[coarse.to];
    const double len = (pb - pa).norm();
    auto range = unmatched_at.equal_range(coarse.from);
    for (auto it = range.first; it != range.second; ++it) {
      EdgeKey k1 = it->second;
      if (k1 == k || used[k1]) continue;
      int h = k1.first == coarse.from ? k1.second : k1.first;
      EdgeKey k2 = key(h, coarse.to);
      auto e2 = edges.find(k2);
      if (e2 == edges.end() || e2->second.size() != 1 || used[k2]) continue;
      const Vec2& ph = m.nodes[h];
      // h must lie on the segment (a, b).
      Vec2 d = pb - pa;
      double s = (ph - pa).dot(d) / d.squaredNorm();
      double off = std::abs(d.x() * (ph - pa).y() - d.y() * (ph - pa).x()) / len;
      if (s <= 0 || s >= 1 || off > 1e-9 * len) continue;
      const HalfEdge& f1 = edges[k1][0];
      const HalfEdge& f2 = e2->second[0];
      // Face (a, h): coarse side s in [0, s]; fine side runs h -> a.
      for (const HalfEdge* fine : {&f1, &f2}) {
        bool first = fine == &f1;
        Vec2 fa = first ? pa : ph, fb = first ? ph : pb;
        Face f = make_face(m, coarse.cell, coarse.edge, first ? 0.0 : s, first ? s : 1.0, fa, fb);
        f.cell[1] = fine->cell;
        f.local_edge[1] = fine->edge;
        if (fine->to != (first ? coarse.from : h))
          throw InputError("mesh", "cells " + number_text(coarse.cell) + " and " +
                                       number_text(fine->cell) + " have opposite orientation");
        f.s_a[1] = 1;
        f.s_b[1] = 0;
        add(std::move(f));
      }
      used[k] = used[k1] = used[k2] = true;
      break;
    }
  }

  // The rest is boundary.
  for (auto& [k, hs] : edges) {
    if (hs.size() != 1 || used[k]) continue;
    const HalfEdge& h = hs[0];
    Face f = make_face(m, h.cell, h.edge, 0, 1, m.nodes[h.from], m.nodes[h.to]);
    auto g = bgroup.find(k);
    f.group = g == bgroup.end() ? -1 : g->second;
    add(std::move(f));
  }
  return t;
}

}  // namespace quadapt
