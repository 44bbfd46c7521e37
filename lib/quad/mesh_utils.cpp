#include "quad/mesh_utils.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <sstream>
#include <unordered_map>

#include "core/error.hpp"

namespace quadapt {

std::vector<std::vector<int>> boundary_loops(const Mesh& m) {
  auto fe = free_edges(m);
  std::unordered_map<int, int> next;
  next.reserve(fe.size());
  for (const auto& e : fe)
    if (!next.emplace(e[0], e[1]).second)
      throw InputError("mesh: boundary node at " + point_text(m.nodes[e[0]]) +
                       " starts two boundary edges (the domain is pinched there)");
  std::vector<std::vector<int>> loops;
  std::unordered_map<int, char> used;
  for (const auto& e : fe) {
    if (used.count(e[0])) continue;
    std::vector<int> loop;
    int v = e[0];
    while (!used.count(v)) {
      used[v] = 1;
      loop.push_back(v);
      auto it = next.find(v);
      if (it == next.end()) throw InputError("mesh: boundary is not closed at node " + point_text(m.nodes[v]));
      v = it->second;
    }
    if (v != e[0]) throw InputError("mesh: boundary does not close into simple loops near " + point_text(m.nodes[v]));
    loops.push_back(std::move(loop));
  }
  return loops;
}

void check_simple_boundary(const Mesh& m, const std::string& source) {
  // on the cells' free edges (a notch touching the boundary pinches it although the listed
  // boundary edges do not); boundary_free_edges leaves out a hanging node's half-edges
  Mesh o = m;
  orient_counter_clockwise(o);
  std::vector<int> edges_at(o.nodes.size(), 0);
  for (const auto& e : boundary_free_edges(o))
    for (int v : e)
      if (++edges_at[v] > 2)
        throw InputError(source, "the domain is pinched: the boundary node at " + point_text(o.nodes[v]) +
                                     " is on more than two boundary edges (cells meet only there); neither BAMG "
                                     "nor lpcvt meshes it");
}

double polygon_area(const Mesh& m, const std::vector<int>& loop) {
  double a = 0;
  const Vec2 o = m.nodes[loop[0]];
  for (size_t i = 0; i < loop.size(); ++i) {
    Vec2 p = m.nodes[loop[i]] - o, q = m.nodes[loop[(i + 1) % loop.size()]] - o;
    a += p.x() * q.y() - p.y() * q.x();
  }
  return 0.5 * a;
}

int orient_counter_clockwise(Mesh& m) {
  int n = 0;
  for (int c = 0; c < m.num_cells(); ++c)
    if (cell_area(m, c) < 0) {
      Cell& cell = m.cells[c];
      std::reverse(cell.v.begin(), cell.v.begin() + cell.nv);
      ++n;
    }
  return n;
}

bool make_triangle_count_even(Mesh& m) {
  if (m.cells.size() % 2 == 0) return false;
  auto fe = free_edges(m);
  if (fe.empty()) throw InputError("mesh: a triangulation without boundary edges cannot be recombined");
  // longest free edge; ties broken by order (deterministic)
  size_t best = 0;
  double lbest = -1;
  for (size_t i = 0; i < fe.size(); ++i) {
    double l = (m.nodes[fe[i][1]] - m.nodes[fe[i][0]]).squaredNorm();
    if (l > lbest) lbest = l, best = i;
  }
  const int a = fe[best][0], b = fe[best][1];
  int cell = -1, local = -1;
  for (int c = 0; c < m.num_cells() && cell < 0; ++c)
    for (int i = 0; i < m.cells[c].nv; ++i)
      if (m.cells[c].v[i] == a && m.cells[c].v[(i + 1) % m.cells[c].nv] == b) {
        cell = c, local = i;
        break;
      }
  Cell& t = m.cells[cell];
  const int opp = t.v[(local + 2) % 3];
  const int mid = m.num_nodes();
  m.nodes.push_back(0.5 * (m.nodes[a] + m.nodes[b]));
  Cell t1, t2;
  t1.nv = t2.nv = 3;
  t1.v = {a, mid, opp, -1};
  t2.v = {mid, b, opp, -1};
  m.cells[cell] = t1;
  m.cells.insert(m.cells.begin() + cell + 1, t2);
  for (size_t i = 0; i < m.boundary.size(); ++i) {
    auto& e = m.boundary[i];
    if ((e.v[0] == a && e.v[1] == b) || (e.v[0] == b && e.v[1] == a)) {
      BoundaryEdge e2 = e;
      int s = e.v[0], f = e.v[1];
      e.v = {s, mid};
      e2.v = {mid, f};
      m.boundary.insert(m.boundary.begin() + i + 1, e2);
      break;
    }
  }
  m.clear_fields();
  return true;
}

}  // namespace quadapt
