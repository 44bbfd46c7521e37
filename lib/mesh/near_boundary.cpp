#include "mesh/near_boundary.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>

#include "core/format.hpp"
#include "mesh/label.hpp"

namespace quadapt {

namespace {

constexpr double kRelTol = 1e-2;                  // tol = kRelTol x the shorter edge's length
constexpr double kCosAntiparallel = 0.86602540378;  // cos 30 degrees

struct Segment {
  Vec2 a, b;
  double len = 0;
  int level = 0;  // ilogb(len): len in [2^level, 2^(level+1))
};

/// A grid bucket of one level (square of side 2^(level+1)) holding one edge of that level.
struct Entry {
  int level;
  long long ix, iy;
  int edge;
  bool operator<(const Entry& o) const {
    return std::tie(level, ix, iy, edge) < std::tie(o.level, o.ix, o.iy, o.edge);
  }
};

long long cell_index(double x, double side) {
  // clamped: an absurd coordinate merges buckets (more candidates), never overflows
  return static_cast<long long>(std::floor(std::clamp(x / side, -1e15, 1e15)));
}

/// The gap of two segments lying on each other (criterion in the header), or -1.
double pair_gap(const Segment& p, const Segment& q) {
  const Segment& e = p.len >= q.len ? p : q;  // the longer one
  const Segment& f = p.len >= q.len ? q : p;
  const Vec2 t = (e.b - e.a) / e.len;
  if ((f.b - f.a).dot(t) >= -kCosAntiparallel * f.len) return -1;
  const double tol = kRelTol * f.len;
  // positions along e of f's ends: sb < sa (opposite directions)
  const double sa = (f.a - e.a).dot(t), sb = (f.b - e.a).dot(t);
  const double lo = std::max(0.0, sb), hi = std::min(e.len, sa);
  if (!(hi - lo > tol)) return -1;
  const Vec2 n(-t.y(), t.x());
  auto offset = [&](double s) {  // distance from e's line of f's point at position s
    const Vec2 x = f.a + (s - sa) / (sb - sa) * (f.b - f.a);
    return std::abs((x - e.a).dot(n));
  };
  const double gap = std::max(offset(lo), offset(hi));
  return gap <= tol ? gap : -1;
}

/// The edges used by one cell, oriented as in it, by node (the lower end) then cell order: free
/// edges as boundary_free_edges finds them, except that a hanging node's coarse edge and its two
/// halves count too — they share a node, so they never lie on each other by the criterion. Linear
/// (counting sort by node), where boundary_free_edges builds the topology: reading a 1e5-cell mesh
/// took 0.2 s, build_topology 0.1 s more, this a few ms.
std::vector<EdgeNodes> edges_of_one_cell(const Mesh& m) {
  const int nn = m.num_nodes();
  std::vector<int> start(static_cast<size_t>(nn) + 2, 0);
  for (const Cell& c : m.cells)
    for (int k = 0; k < c.nv; ++k) ++start[std::min(c.v[k], c.v[(k + 1) % c.nv]) + 2];
  for (int i = 2; i <= nn + 1; ++i) start[i] += start[i - 1];
  std::vector<EdgeNodes> by_node(start[nn + 1]);  // directed, grouped by the lower end
  for (const Cell& c : m.cells)
    for (int k = 0; k < c.nv; ++k) {
      const int a = c.v[k], b = c.v[(k + 1) % c.nv];
      by_node[start[std::min(a, b) + 1]++] = {a, b};
    }
  std::vector<EdgeNodes> out;
  for (int v = 0; v < nn; ++v)  // the edges of lower end v: by_node[start[v], start[v + 1])
    for (int i = start[v]; i < start[v + 1]; ++i) {
      const int other = by_node[i][0] + by_node[i][1] - v;
      int uses = 0;
      for (int j = start[v]; j < start[v + 1]; ++j) uses += by_node[j][0] + by_node[j][1] - v == other;
      if (uses == 1) out.push_back(by_node[i]);
    }
  return out;
}

}  // namespace

std::vector<EdgeOverlap> overlapping_edges(const Mesh& m, const std::vector<EdgeNodes>& edges) {
  const int n = static_cast<int>(edges.size());
  std::vector<Segment> seg(n);
  std::vector<char> usable(n, 0);
  std::vector<Entry> grid;
  grid.reserve(4 * static_cast<size_t>(n));
  std::vector<int> levels;
  for (int i = 0; i < n; ++i) {
    Segment& s = seg[i];
    s.a = m.nodes[edges[i][0]];
    s.b = m.nodes[edges[i][1]];
    s.len = (s.b - s.a).norm();
    if (!(s.len > 0) || !std::isfinite(s.len)) continue;
    usable[i] = 1;
    s.level = std::ilogb(s.len);
    levels.push_back(s.level);
    // the edge in every bucket of its level its bounding box touches (at most 2 x 2: its length
    // is below the bucket's side)
    const double side = std::ldexp(1.0, s.level + 1);
    const long long x0 = cell_index(std::min(s.a.x(), s.b.x()), side), x1 = cell_index(std::max(s.a.x(), s.b.x()), side);
    const long long y0 = cell_index(std::min(s.a.y(), s.b.y()), side), y1 = cell_index(std::max(s.a.y(), s.b.y()), side);
    for (long long ix = x0; ix <= x1; ++ix)
      for (long long iy = y0; iy <= y1; ++iy) grid.push_back({s.level, ix, iy, i});
  }
  std::sort(grid.begin(), grid.end());
  std::sort(levels.begin(), levels.end());
  levels.erase(std::unique(levels.begin(), levels.end()), levels.end());

  // Candidates: for each edge, the edges at least as long (levels >= its own) in the buckets
  // touched by its bounding box grown by its tol. A pair that lies on each other has points
  // within tol of each other, so the longer edge is in one of those buckets.
  std::vector<std::pair<int, int>> candidates;
  for (int i = 0; i < n; ++i) {
    if (!usable[i]) continue;
    const Segment& s = seg[i];
    const double tol = kRelTol * s.len;
    const double bx0 = std::min(s.a.x(), s.b.x()) - tol, bx1 = std::max(s.a.x(), s.b.x()) + tol;
    const double by0 = std::min(s.a.y(), s.b.y()) - tol, by1 = std::max(s.a.y(), s.b.y()) + tol;
    for (auto lv = std::lower_bound(levels.begin(), levels.end(), s.level); lv != levels.end(); ++lv) {
      const double side = std::ldexp(1.0, *lv + 1);
      for (long long ix = cell_index(bx0, side), x1 = cell_index(bx1, side); ix <= x1; ++ix)
        for (long long iy = cell_index(by0, side), y1 = cell_index(by1, side); iy <= y1; ++iy) {
          auto it = std::lower_bound(grid.begin(), grid.end(), Entry{*lv, ix, iy, -1});
          for (; it != grid.end() && it->level == *lv && it->ix == ix && it->iy == iy; ++it)
            if (it->edge != i) candidates.emplace_back(std::min(i, it->edge), std::max(i, it->edge));
        }
    }
  }
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());

  std::vector<EdgeOverlap> out;
  for (const auto& [i, j] : candidates) {
    const EdgeNodes &a = edges[i], &b = edges[j];
    if (a[0] == b[0] || a[0] == b[1] || a[1] == b[0] || a[1] == b[1]) continue;
    const double gap = pair_gap(seg[i], seg[j]);
    if (gap >= 0) out.push_back({i, j, gap});
  }
  return out;
}

std::vector<std::string> boundary_warnings(const Mesh& m) {
  const std::vector<EdgeNodes> edges = edges_of_one_cell(m);
  const std::vector<EdgeOverlap> pairs = overlapping_edges(m, edges);
  if (pairs.empty()) return {};
  std::vector<int> involved;
  double gap = 0;
  for (const EdgeOverlap& p : pairs) {
    involved.push_back(p.e);
    involved.push_back(p.f);
    gap = std::max(gap, p.gap);
  }
  std::sort(involved.begin(), involved.end());
  const size_t count = std::unique(involved.begin(), involved.end()) - involved.begin();
  auto edge_text = [&](int e) { return point_text(m.nodes[edges[e][0]]) + " - " + point_text(m.nodes[edges[e][1]]); };
  return {std::to_string(count) + " boundary edges lie on other boundary edges (" + std::to_string(pairs.size()) +
          (pairs.size() == 1 ? " pair" : " pairs") + ", at most " + sci(gap) + " apart; first: " +
          edge_text(pairs[0].e) + " on " + edge_text(pairs[0].f) +
          "): two blocks whose shared nodes were not merged, solved as a domain with a slit (Gmsh: "
          "Geometry.Tolerance above the gap, then Coherence Mesh; after meshing); ignore this if the slit (a crack) "
          "is meant"};
}

}  // namespace quadapt
