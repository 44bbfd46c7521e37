#include "mesh/boundary.hpp"

#include <algorithm>
#include <cstdint>
#include <sstream>
#include <cmath>
#include <map>
#include <set>
#include <unordered_map>

#include "core/error.hpp"
#include "mesh/topology.hpp"

namespace quadapt {

namespace {
using Key = std::pair<int, int>;
Key key(int a, int b) { return a < b ? Key{a, b} : Key{b, a}; }

bool lower(const Vec2& p, const Vec2& q) { return p.y() < q.y() || (p.y() == q.y() && p.x() < q.x()); }

constexpr double kCollinear = 1e-6;  // radians: below this two edges are on one line
}  // namespace

std::uint64_t directed_edge_key(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}
std::uint64_t edge_key(int a, int b) { return a < b ? directed_edge_key(a, b) : directed_edge_key(b, a); }

std::vector<EdgeNodes> free_edges(const Mesh& m, bool strict) {
  // directed edge -> count; undirected -> count
  std::unordered_map<std::uint64_t, int> directed, undirected;  // edge key -> uses
  directed.reserve(4 * m.cells.size());
  undirected.reserve(4 * m.cells.size());
  for (const auto& c : m.cells)
    for (int i = 0; i < c.nv; ++i) {
      int a = c.v[i], b = c.v[(i + 1) % c.nv];
      if (++directed[directed_edge_key(a, b)] > 1 && strict)
        throw InputError("mesh: edge between nodes at " + point_text(m.nodes[a]) + " and " + point_text(m.nodes[b]) +
                         " is used twice in the same direction (inconsistent orientation or overlapping cells)");
      if (++undirected[edge_key(a, b)] > 2 && strict)
        throw InputError("mesh: edge between nodes at " + point_text(m.nodes[a]) + " and " + point_text(m.nodes[b]) +
                         " is shared by more than two cells");
    }
  std::vector<EdgeNodes> out;
  for (const auto& c : m.cells)
    for (int i = 0; i < c.nv; ++i) {
      int a = c.v[i], b = c.v[(i + 1) % c.nv];
      if (undirected[edge_key(a, b)] == 1) out.push_back({a, b});
    }
  return out;
}


std::vector<EdgeNodes> boundary_free_edges(const Mesh& m) {
  std::vector<EdgeNodes> out;
  try {
    Topology t = build_topology(m);
    for (const Face& f : t.faces) {
      if (!f.is_boundary()) continue;
      const Cell& c = m.cells[f.cell[0]];
      const int e = f.local_edge[0];
      out.push_back({c.v[e], c.v[(e + 1) % c.nv]});
    }
    return out;
  } catch (const InputError&) {
    // Broken topology (reported by validate_mesh): fall back to edges used once.
  }
  return free_edges(m, false);
}

bool is_unit_square(const Mesh& m, double tol) {
  if (m.cells.empty()) return false;
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  for (const Cell& c : m.cells)
    for (int i = 0; i < c.nv; ++i) {
      const Vec2& p = m.nodes[c.v[i]];
      x0 = std::min(x0, p.x());
      x1 = std::max(x1, p.x());
      y0 = std::min(y0, p.y());
      y1 = std::max(y1, p.y());
    }
  if (std::abs(x0) > tol || std::abs(y0) > tol || std::abs(x1 - 1) > tol || std::abs(y1 - 1) > tol) return false;
  return std::abs(std::abs(total_area(m)) - 1.0) <= tol;
}

std::string unit_square_side(const Vec2& a, const Vec2& b, double tol) {
  if (std::abs(a.y()) <= tol && std::abs(b.y()) <= tol) return "bottom";
  if (std::abs(a.x() - 1) <= tol && std::abs(b.x() - 1) <= tol) return "right";
  if (std::abs(a.y() - 1) <= tol && std::abs(b.y() - 1) <= tol) return "top";
  if (std::abs(a.x()) <= tol && std::abs(b.x()) <= tol) return "left";
  return "";
}

std::vector<std::vector<int>> split_into_curves(const Mesh& m, const std::vector<EdgeNodes>& edges,
                                                const BoundaryOptions& opt) {
  const int n = static_cast<int>(edges.size());
  std::unordered_map<int, std::vector<int>> out;
  std::unordered_map<int, int> indeg;
  for (int i = 0; i < n; ++i) {
    out[edges[i][0]].push_back(i);
    ++indeg[edges[i][1]];
  }
  std::vector<char> used(n, 0);
  struct Chain {
    std::vector<int> e;
    bool closed = false;
  };
  std::vector<Chain> chains;
  auto walk = [&](int start) {
    Chain ch;
    int e = start;
    while (e >= 0 && !used[e]) {
      used[e] = 1;
      ch.e.push_back(e);
      int next = -1;
      auto it = out.find(edges[e][1]);
      if (it != out.end())
        for (int cand : it->second)
          if (!used[cand]) { next = cand; break; }
      e = next;
    }
    ch.closed = edges[ch.e.back()][1] == edges[ch.e.front()][0];
    chains.push_back(std::move(ch));
  };
  for (int i = 0; i < n; ++i)  // open chains start where no edge comes in
    if (!used[i] && indeg[edges[i][0]] == 0) walk(i);
  for (int i = 0; i < n; ++i)
    if (!used[i]) walk(i);

  const double corner = opt.corner_angle_deg * M_PI / 180.0;
  auto dir = [&](int e) {
    Vec2 d = m.nodes[edges[e][1]] - m.nodes[edges[e][0]];
    double len = d.norm();
    return len > 0 ? Vec2(d / len) : Vec2(0, 0);
  };
  struct Ordered {
    Vec2 low;
    int low_node;
    std::vector<std::vector<int>> curves;
  };
  std::vector<Ordered> result;
  for (const Chain& ch : chains) {
    const int k = static_cast<int>(ch.e.size());
    // turn[j]: turning angle at the start node of ch.e[j] (between edge j-1 and edge j).
    std::vector<double> turn(k, 0.0);
    std::vector<char> valid(k, 0);
    for (int j = 0; j < k; ++j) {
      if (j == 0 && !ch.closed) continue;
      Vec2 a = dir(ch.e[(j - 1 + k) % k]), b = dir(ch.e[j]);
      turn[j] = std::abs(std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b)));
      valid[j] = 1;
    }
    auto straight = [&](int j) {  // node j joins two collinear edges
      if (!ch.closed && (j <= 0 || j >= k)) return false;
      j = (j % k + k) % k;
      return valid[j] && turn[j] < kCollinear;
    };
    std::vector<int> corners;
    for (int j = 0; j < k; ++j) {
      if (!valid[j]) continue;
      bool is_corner = turn[j] > corner || (turn[j] >= kCollinear && (straight(j - 1) || straight(j + 1)));
      if (is_corner) corners.push_back(j);
    }
    Ordered o;
    o.low_node = edges[ch.e[0]][0];
    for (int e : ch.e) {
      int v = edges[e][0];
      if (lower(m.nodes[v], m.nodes[o.low_node]) || (m.nodes[v] == m.nodes[o.low_node] && v < o.low_node)) o.low_node = v;
    }
    o.low = m.nodes[o.low_node];
    if (!ch.closed) {
      std::vector<int> cur;
      for (int j = 0; j < k; ++j) {
        if (!cur.empty() && std::find(corners.begin(), corners.end(), j) != corners.end()) {
          o.curves.push_back(cur);
          cur.clear();
        }
        cur.push_back(ch.e[j]);
      }
      o.curves.push_back(cur);
    } else {
      // Start at the lowest corner (or, without corners, at the lowest node).
      int start = 0;
      if (corners.empty()) {
        for (int j = 0; j < k; ++j)
          if (edges[ch.e[j]][0] == o.low_node) start = j;
      } else {
        start = corners[0];
        for (int j : corners)
          if (lower(m.nodes[edges[ch.e[j]][0]], m.nodes[edges[ch.e[start]][0]])) start = j;
      }
      std::vector<int> cur;
      for (int s = 0; s < k; ++s) {
        int j = (start + s) % k;
        if (!cur.empty() && std::find(corners.begin(), corners.end(), j) != corners.end()) {
          o.curves.push_back(cur);
          cur.clear();
        }
        cur.push_back(ch.e[j]);
      }
      o.curves.push_back(cur);
    }
    result.push_back(std::move(o));
  }
  std::stable_sort(result.begin(), result.end(), [](const Ordered& a, const Ordered& b) {
    if (a.low != b.low) return lower(a.low, b.low);
    return a.low_node < b.low_node;
  });
  std::vector<std::vector<int>> curves;
  for (auto& o : result)
    for (auto& c : o.curves) curves.push_back(std::move(c));
  return curves;
}

int complete_boundary(Mesh& m, const BoundaryOptions& opt) {
  std::set<Key> covered;
  for (const BoundaryEdge& be : m.boundary) covered.insert(key(be.v[0], be.v[1]));
  {
    // Fast path (no topology): every edge used by one cell only is covered already. Free
    // edges are a subset of those (hanging-node halves are used once but are interior).
    std::unordered_map<unsigned long long, int> uses;
    uses.reserve(m.cells.size() * 4);
    for (const Cell& c : m.cells)
      for (int e = 0; e < c.nv; ++e) {
        Key k = key(c.v[e], c.v[(e + 1) % c.nv]);
        ++uses[(static_cast<unsigned long long>(static_cast<unsigned>(k.first)) << 32) | static_cast<unsigned>(k.second)];
      }
    bool complete = true;
    for (const auto& [k, n] : uses)
      if (n == 1 && !covered.count(Key{static_cast<int>(k >> 32), static_cast<int>(k & 0xffffffffu)})) {
        complete = false;
        break;
      }
    if (complete) return 0;
  }
  std::vector<EdgeNodes> missing;
  for (const EdgeNodes& e : boundary_free_edges(m))
    if (!covered.count(key(e[0], e[1]))) missing.push_back(e);
  if (missing.empty()) return 0;

  const bool square = is_unit_square(m);
  int k = 1;
  for (const std::vector<int>& curve : split_into_curves(m, missing, opt)) {
    std::string name;
    if (square) {
      std::string side = unit_square_side(m.nodes[missing[curve[0]][0]], m.nodes[missing[curve[0]][1]]);
      for (int e : curve)
        if (unit_square_side(m.nodes[missing[e][0]], m.nodes[missing[e][1]]) != side) side.clear();
      if (!side.empty() && m.find_group(side) < 0) name = side;
    }
    if (name.empty()) {
      while (m.find_group("boundary_" + std::to_string(k)) >= 0) ++k;
      name = "boundary_" + std::to_string(k++);
    }
    m.groups.push_back({m.free_tag(), name, true});
    const int g = static_cast<int>(m.groups.size()) - 1;
    for (int e : curve) m.boundary.push_back({missing[e], g});
  }
  return static_cast<int>(missing.size());
}

std::vector<char> boundary_node_flags(const Mesh& m) {
  std::vector<char> f(m.nodes.size(), 0);
  std::unordered_map<std::uint64_t, int> count;
  count.reserve(4 * m.cells.size());
  for (const auto& c : m.cells)
    for (int i = 0; i < c.nv; ++i) ++count[edge_key(c.v[i], c.v[(i + 1) % c.nv])];
  for (const auto& c : m.cells)
    for (int i = 0; i < c.nv; ++i) {
      int a = c.v[i], b = c.v[(i + 1) % c.nv];
      if (count[edge_key(a, b)] == 1) f[a] = f[b] = 1;
    }
  for (const auto& e : m.boundary) f[e.v[0]] = f[e.v[1]] = 1;
  return f;
}

}  // namespace quadapt
