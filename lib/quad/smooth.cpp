#include "quad/smooth.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include <Eigen/LU>

#include "core/error.hpp"
#include "quad/mesh_utils.hpp"
#include "quad/quality_summary.hpp"

namespace quadapt {

namespace {
constexpr double kPi = 3.14159265358979323846;

struct EdgeCells {
  int a = -1, b = -1;  // cells sharing the edge
};

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

int local_index(const Cell& c, int v) {
  for (int k = 0; k < c.nv; ++k)
    if (c.v[k] == v) return k;
  return -1;
}

// Interior angle (radians) of cell c at its local vertex k, measured after the linear map T
// (the identity in physical space; the frame's M in its metric space).
double corner(const Mesh& m, const Cell& c, int k, const Mat2& T) {
  const Vec2& p = m.nodes[c.v[k]];
  Vec2 en = T * (m.nodes[c.v[(k + 1) % c.nv]] - p), ep = T * (m.nodes[c.v[(k + c.nv - 1) % c.nv]] - p);
  double a = std::atan2(cross2(en, ep), en.dot(ep));
  return a < 0 ? a + 2 * kPi : a;
}

bool cell_valid(const Mesh& m, const Cell& c) {
  for (int k = 0; k < c.nv; ++k) {
    const Vec2& p = m.nodes[c.v[k]];
    Vec2 en = m.nodes[c.v[(k + 1) % c.nv]] - p, ep = m.nodes[c.v[(k + c.nv - 1) % c.nv]] - p;
    if (!(cross2(en, ep) > 0)) return false;
  }
  return true;
}

// Smallest corner angle and smallest corner sine (scaled Jacobian) over the cells.
struct LocalQuality {
  double angle = 1e300, sine = 1e300;
};
LocalQuality cells_quality(const Mesh& m, const std::vector<int>& cells, const Mat2& T) {
  LocalQuality q;
  for (int c : cells)
    for (int k = 0; k < m.cells[c].nv; ++k) {
      const double a = corner(m, m.cells[c], k, T);
      q.angle = std::min(q.angle, a);
      q.sine = std::min(q.sine, std::sin(a));
    }
  return q;
}
}  // namespace

SmoothStats angle_smooth(Mesh& m, const SmoothOptions& opt, const NodeMetric& metric) {
  SmoothStats st;
  const int nn = m.num_nodes();
  std::vector<char> fixed = boundary_node_flags(m);
  std::vector<std::vector<int>> node_cells(nn);
  std::unordered_map<std::uint64_t, EdgeCells> edges;
  edges.reserve(4 * m.cells.size());
  auto ukey = [](int a, int b) {
    if (a > b) std::swap(a, b);
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
  };
  for (int c = 0; c < m.num_cells(); ++c) {
    const Cell& cell = m.cells[c];
    for (int k = 0; k < cell.nv; ++k) {
      node_cells[cell.v[k]].push_back(c);
      auto& e = edges[ukey(cell.v[k], cell.v[(k + 1) % cell.nv])];
      if (e.a < 0) e.a = c;
      else if (e.b < 0) e.b = c;
      else throw InputError("mesh: an edge is shared by more than two cells");
    }
  }
  // Edge neighbours of each node, in a deterministic order.
  std::vector<std::vector<int>> nbrs(nn);
  for (int v = 0; v < nn; ++v) {
    for (int c : node_cells[v]) {
      const Cell& cell = m.cells[c];
      int k = local_index(cell, v);
      for (int w : {cell.v[(k + 1) % cell.nv], cell.v[(k + cell.nv - 1) % cell.nv]})
        if (std::find(nbrs[v].begin(), nbrs[v].end(), w) == nbrs[v].end()) nbrs[v].push_back(w);
    }
    // A node with an edge that has a single cell is on the boundary (or a hanging node).
    for (int w : nbrs[v]) {
      const auto& e = edges[ukey(v, w)];
      if (e.b < 0) fixed[v] = 1;
    }
    if (node_cells[v].empty()) fixed[v] = 1;
  }
  for (int v = 0; v < nn; ++v) st.interior_nodes += fixed[v] ? 0 : 1;

  st.min_angle_before = quality_summary(m).min_angle_deg;
  for (int sweep = 0; sweep < opt.sweeps; ++sweep) {
    double max_rel = 0;
    for (int i = 0; i < nn; ++i) {
      if (fixed[i]) continue;
      const Vec2 xi = m.nodes[i];
      // The step is made in the space mapped by T (T x_i's star), then mapped back.
      const Mat2 T = metric ? metric(xi) : Mat2::Identity();
      const Mat2 Tinv = T.inverse();
      Vec2 sum = Vec2::Zero();
      double size = 0;
      int n = 0;
      for (int j : nbrs[i]) {
        const auto& e = edges[ukey(i, j)];
        const Cell& A = m.cells[e.a];
        const Cell& B = m.cells[e.b];
        const int ka = local_index(A, j), kb = local_index(B, j);
        const double aA = corner(m, A, ka, T), aB = corner(m, B, kb, T);
        const double wA = A.nv == 3 ? 60.0 : 90.0, wB = B.nv == 3 ? 60.0 : 90.0;
        const double target = (aA + aB) * wA / (wA + wB);
        // A lies counter-clockwise of (j -> i) when i follows j in A's vertex order.
        const double s = A.v[(ka + 1) % A.nv] == i ? 1.0 : -1.0;
        const double d = s * (aA - target);
        const Vec2 u = T * (xi - m.nodes[j]);
        const double cs = std::cos(d), sn = std::sin(d);
        sum += m.nodes[j] + Tinv * Vec2(cs * u.x() - sn * u.y(), sn * u.x() + cs * u.y());
        size += (xi - m.nodes[j]).norm();
        ++n;
      }
      if (n == 0) continue;
      size /= n;
      const Vec2 step = sum / n - xi;
      if (!(step.norm() > 0) || !std::isfinite(step.x()) || !std::isfinite(step.y())) continue;
      const auto& cells = node_cells[i];
      std::vector<char> was_valid(cells.size());
      for (size_t k = 0; k < cells.size(); ++k) was_valid[k] = cell_valid(m, m.cells[cells[k]]);
      const LocalQuality before = cells_quality(m, cells, T);
      bool accepted = false;
      double f = 1.0;
      for (int h = 0; h <= opt.max_halvings; ++h, f *= 0.5) {
        m.nodes[i] = xi + f * step;
        bool ok = true;
        for (size_t k = 0; k < cells.size() && ok; ++k)
          if (was_valid[k] && !cell_valid(m, m.cells[cells[k]])) ok = false;
        const LocalQuality after = ok ? cells_quality(m, cells, T) : LocalQuality{};
        if (ok && after.angle >= before.angle && after.sine >= std::min(before.sine, opt.min_sine)) {
          accepted = true;
          (h == 0 ? st.moves_full : st.moves_reduced)++;
          st.max_displacement = std::max(st.max_displacement, f * step.norm());
          max_rel = std::max(max_rel, f * step.norm() / size);
          break;
        }
      }
      if (!accepted) {
        m.nodes[i] = xi;
        ++st.moves_rejected;
      }
    }
    ++st.sweeps;
    if (max_rel <= opt.tolerance) break;
  }
  st.min_angle_after = quality_summary(m).min_angle_deg;
  return st;
}

}  // namespace quadapt
