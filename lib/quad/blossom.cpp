#include "quad/blossom.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <unordered_map>

#include "core/error.hpp"
#include "mesh/label.hpp"
#include "gmsh/gmsh_recombine.hpp"
#include "quad/mesh_utils.hpp"

namespace quadapt {

namespace {

struct PointKey {
  double x, y;
  bool operator<(const PointKey& o) const { return x < o.x || (x == o.x && y < o.y); }
};

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

GmshRecombined run_gmsh(const Mesh& tri, const std::vector<std::vector<int>>& loops, const std::vector<char>& on_boundary,
                        const BlossomOptions& opt, bool cleanup) {
  // Order loops: the one of largest positive area is the outer loop.
  std::vector<int> order(loops.size());
  for (size_t i = 0; i < loops.size(); ++i) order[i] = static_cast<int>(i);
  std::vector<double> la(loops.size());
  for (size_t i = 0; i < loops.size(); ++i) la[i] = polygon_area(tri, loops[i]);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return la[a] > la[b]; });
  std::vector<std::vector<int>> ordered;
  for (int li : order) ordered.push_back(loops[li]);
  GmshRecombineOptions g;
  g.algorithm = opt.algorithm;
  g.optimize_topology = cleanup ? opt.optimize_topology : 0;
  g.smoothing = cleanup ? opt.smoothing : 0;
  return gmsh_recombine(tri, ordered, on_boundary, g);
}

// Input node of each answer node with exactly the same coordinates, or -1.
std::vector<int> match_nodes(const Mesh& tri, const std::vector<Vec2>& nodes, const std::vector<char>* only) {
  std::map<PointKey, int> index;
  for (size_t v = 0; v < tri.nodes.size(); ++v)
    if (!only || (*only)[v]) index[{tri.nodes[v].x(), tri.nodes[v].y()}] = int(v);
  std::vector<int> r(nodes.size(), -1);
  for (size_t i = 0; i < nodes.size(); ++i) {
    auto it = index.find({nodes[i].x(), nodes[i].y()});
    if (it != index.end()) r[i] = it->second;
  }
  return r;
}

// Pairing mode: Gmsh's quads as pairs of input triangles.
Mesh pairing(const Mesh& tri, const GmshRecombined& ans, const BlossomOptions& opt, BlossomStats& st) {
  const std::vector<int> to_input = match_nodes(tri, ans.nodes, nullptr);
  auto key3 = [](int a, int b, int c) {
    std::array<int, 3> s{{a, b, c}};
    std::sort(s.begin(), s.end());
    return (static_cast<std::uint64_t>(s[0]) << 42) ^ (static_cast<std::uint64_t>(s[1]) << 21) ^ static_cast<std::uint64_t>(s[2]);
  };
  std::unordered_map<std::uint64_t, int> tri_index;
  tri_index.reserve(2 * tri.cells.size());
  for (int t = 0; t < tri.num_cells(); ++t) tri_index[key3(tri.cells[t].v[0], tri.cells[t].v[1], tri.cells[t].v[2])] = t;
  std::vector<int> partner(tri.cells.size(), -1);
  auto convex_enough = [&](const std::array<int, 4>& q) {
    for (int i = 0; i < 4; ++i) {
      const Vec2& p = tri.nodes[q[i]];
      Vec2 en = tri.nodes[q[(i + 1) % 4]] - p, ep = tri.nodes[q[(i + 3) % 4]] - p;
      double l = en.norm() * ep.norm();
      if (!(l > 0) || cross2(en, ep) / l < opt.min_pair_jacobian) return false;
    }
    return true;
  };
  for (const Cell& c : ans.cells) {
    if (c.nv != 4) continue;
    ++st.gmsh_quads;
    std::array<int, 4> v;
    bool known = true;
    for (int i = 0; i < 4; ++i) {
      v[i] = to_input[c.v[i]];
      if (v[i] < 0) known = false;
    }
    bool used = false;
    if (known) {
      for (int d = 0; d < 2 && !used; ++d) {  // diagonal (v[d], v[d+2])
        auto i1 = tri_index.find(key3(v[d], v[d + 1], v[(d + 2) % 4]));
        auto i2 = tri_index.find(key3(v[d], v[(d + 2) % 4], v[(d + 3) % 4]));
        if (i1 == tri_index.end() || i2 == tri_index.end()) continue;
        const int t1 = i1->second, t2 = i2->second;
        if (t1 == t2 || partner[t1] >= 0 || partner[t2] >= 0) continue;
        // quad in the input's counter-clockwise order: t1 = (k, k+1, k+2) with the shared edge
        // (k+1, k+2) and t2's opposite vertex o: (k, k+1, o, k+2)
        const Cell& a = tri.cells[t1];
        const Cell& b = tri.cells[t2];
        int k = 0;
        while (k < 3 && (a.v[k] == b.v[0] || a.v[k] == b.v[1] || a.v[k] == b.v[2])) ++k;
        int o = 0;
        while (o < 3 && (b.v[o] == a.v[0] || b.v[o] == a.v[1] || b.v[o] == a.v[2])) ++o;
        if (k == 3 || o == 3) continue;
        std::array<int, 4> q = {a.v[k], a.v[(k + 1) % 3], b.v[o], a.v[(k + 2) % 3]};
        if (!convex_enough(q)) continue;
        partner[t1] = t2;
        partner[t2] = t1;
        used = true;
      }
    }
    if (!used) ++st.rejected_pairs;
  }
  // Left-over neighbours (Gmsh leaves triangles unmatched when their pair's physical-space
  // quality is below its threshold, common on anisotropic meshes): pair them greedily, best
  // corner scaled Jacobian first, when the quad is convex enough.
  {
    std::unordered_map<std::uint64_t, std::array<int, 2>> edge_tris;
    auto ekey = [](int a, int b) {
      if (a > b) std::swap(a, b);
      return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
    };
    for (int t = 0; t < tri.num_cells(); ++t)
      if (partner[t] < 0)
        for (int i = 0; i < 3; ++i) {
          auto& e = edge_tris.try_emplace(ekey(tri.cells[t].v[i], tri.cells[t].v[(i + 1) % 3]), std::array<int, 2>{{-1, -1}}).first->second;
          (e[0] < 0 ? e[0] : e[1]) = t;
        }
    struct Cand {
      double q;
      int t1, t2;
    };
    std::vector<Cand> cands;
    for (const auto& [k, e] : edge_tris) {
      if (e[0] < 0 || e[1] < 0) continue;
      const Cell& a = tri.cells[e[0]];
      const Cell& b = tri.cells[e[1]];
      int k1 = 0;
      while (k1 < 3 && (a.v[k1] == b.v[0] || a.v[k1] == b.v[1] || a.v[k1] == b.v[2])) ++k1;
      int o = 0;
      while (o < 3 && (b.v[o] == a.v[0] || b.v[o] == a.v[1] || b.v[o] == a.v[2])) ++o;
      if (k1 == 3 || o == 3) continue;
      std::array<int, 4> q = {a.v[k1], a.v[(k1 + 1) % 3], b.v[o], a.v[(k1 + 2) % 3]};
      if (!convex_enough(q)) continue;
      double qmin = 1;
      for (int i = 0; i < 4; ++i) {
        const Vec2& p = tri.nodes[q[i]];
        Vec2 en = tri.nodes[q[(i + 1) % 4]] - p, ep = tri.nodes[q[(i + 3) % 4]] - p;
        qmin = std::min(qmin, cross2(en, ep) / (en.norm() * ep.norm()));
      }
      cands.push_back({qmin, std::min(e[0], e[1]), std::max(e[0], e[1])});
    }
    std::sort(cands.begin(), cands.end(), [](const Cand& x, const Cand& y) {
      return x.q > y.q || (x.q == y.q && (x.t1 < y.t1 || (x.t1 == y.t1 && x.t2 < y.t2)));
    });
    for (const auto& c : cands)
      if (partner[c.t1] < 0 && partner[c.t2] < 0) {
        partner[c.t1] = c.t2;
        partner[c.t2] = c.t1;
        ++st.greedy_pairs;
      }
  }
  Mesh out;
  out.nodes = tri.nodes;
  out.groups = tri.groups;
  out.boundary = tri.boundary;
  out.domain_name = tri.domain_name;
  out.domain_tag = tri.domain_tag;
  for (int t = 0; t < tri.num_cells(); ++t) {
    const int p = partner[t];
    if (p < 0) {
      out.cells.push_back(tri.cells[t]);
      continue;
    }
    if (p < t) continue;  // emitted with its partner
    const Cell& a = tri.cells[t];
    const Cell& b = tri.cells[p];
    int k = 0;
    while (a.v[k] == b.v[0] || a.v[k] == b.v[1] || a.v[k] == b.v[2]) ++k;
    int o = 0;
    while (b.v[o] == a.v[0] || b.v[o] == a.v[1] || b.v[o] == a.v[2]) ++o;
    Cell q;
    q.nv = 4;
    q.v = {a.v[k], a.v[(k + 1) % 3], b.v[o], a.v[(k + 2) % 3]};
    out.cells.push_back(q);
  }
  return out;
}

// Clean-up mode: Gmsh's mesh as it is, checked. Throws ExternalError when a check fails.
Mesh take_cleanup(const Mesh& tri, const GmshRecombined& ans, const std::vector<char>& on_boundary,
                  const std::vector<std::vector<int>>& loops, BlossomStats& st) {
  Mesh out;
  out.nodes = ans.nodes;
  out.cells = ans.cells;
  out.groups = tri.groups;
  out.domain_name = tri.domain_name;
  out.domain_tag = tri.domain_tag;
  for (const Cell& c : ans.cells) st.gmsh_quads += c.nv == 4 ? 1 : 0;
  const std::vector<int> to_input = match_nodes(tri, ans.nodes, &on_boundary);
  std::vector<int> old_to_new(tri.nodes.size(), -1);
  for (size_t i = 0; i < to_input.size(); ++i)
    if (to_input[i] >= 0) old_to_new[to_input[i]] = int(i);
  st.reoriented = orient_counter_clockwise(out);
  for (const auto& e : tri.boundary) {
    int a = old_to_new[e.v[0]], b = old_to_new[e.v[1]];
    if (a < 0 || b < 0) throw ExternalError("Gmsh recombination moved or removed a boundary node");
    out.boundary.push_back({{a, b}, e.group});
  }
  const double area_in = total_area(tri);
  double area_abs = 0;
  for (int c = 0; c < out.num_cells(); ++c) area_abs += std::abs(cell_area(out, c));
  if (std::abs(area_abs - area_in) > 1e-9 * std::abs(area_in))
    throw ExternalError("Gmsh recombination produced overlapping or missing elements (area " +
                        std::to_string(area_abs) + " instead of " + std::to_string(area_in) + "; " +
                        std::to_string(st.reoriented) + " of " + std::to_string(out.num_cells()) +
                        " cells came back clockwise)");
  std::vector<std::array<int, 2>> fe;
  try {
    fe = free_edges(out);
  } catch (const InputError& e) {
    throw ExternalError(std::string("Gmsh recombination produced an invalid mesh: ") + e.what());
  }
  size_t nfree_in = 0;
  for (const auto& l : loops) nfree_in += l.size();
  if (fe.size() != nfree_in)
    throw ExternalError("Gmsh recombination changed the boundary (" + std::to_string(fe.size()) +
                        " free edges instead of " + std::to_string(nfree_in) + ")");
  for (int c = 0; c < out.num_cells(); ++c) {
    const Cell& cell = out.cells[c];
    for (int i = 0; i < cell.nv; ++i) {
      Vec2 p = out.nodes[cell.v[i]];
      Vec2 en = out.nodes[cell.v[(i + 1) % cell.nv]] - p, ep = out.nodes[cell.v[(i + cell.nv - 1) % cell.nv]] - p;
      if (!(cross2(en, ep) > 0))
        throw ExternalError("Gmsh recombination produced an inverted or degenerate " + cell_label(out, c));
    }
  }
  return out;
}

}  // namespace

Mesh blossom_recombine(const Mesh& tri, const BlossomOptions& opt, BlossomStats* stats) {
  if (!tri.all_triangles()) throw InputError("mesh: Blossom recombination needs a triangulation");
  const auto loops = boundary_loops(tri);
  if (loops.empty()) throw InputError("mesh: the triangulation has no boundary");
  std::vector<char> on_boundary(tri.nodes.size(), 0);
  for (const auto& l : loops)
    for (int v : l) on_boundary[v] = 1;

  BlossomStats st;
  st.triangles_in = tri.num_cells();
  Mesh out;
  bool done = false;
  if (opt.gmsh_cleanup) {
    try {
      GmshRecombined ans = run_gmsh(tri, loops, on_boundary, opt, true);
      out = take_cleanup(tri, ans, on_boundary, loops, st);
      done = true;
    } catch (const ExternalError& e) {
      st = BlossomStats();
      st.triangles_in = tri.num_cells();
      st.fell_back = true;
      st.fallback_reason = e.what();
    }
  }
  if (!done) {
    GmshRecombined ans = run_gmsh(tri, loops, on_boundary, opt, false);
    out = pairing(tri, ans, opt, st);
  }
  st.quads = out.num_quads();
  st.triangles = out.num_triangles();
  if (stats) *stats = st;
  return out;
}

}  // namespace quadapt
