#include "quad/smooth.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <unordered_map>

#include <Eigen/LU>

#include "core/error.hpp"
#include "mesh/boundary.hpp"
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

// The sines of corner k of a cell (the scaled Jacobian; negative at a reflex corner) after the
// map T and in physical space, from one pair of edge differences: sin(angle) =
// cross(e_next, e_prev) / (|e_next| |e_prev|), no trigonometry.
void corner_sines(const Mesh& m, const Cell& cell, int k, const Mat2& T, double& sine_T, double& sine_phys) {
  const Vec2& p = m.nodes[cell.v[k]];
  const Vec2 dn = m.nodes[cell.v[(k + 1) % cell.nv]] - p, dp = m.nodes[cell.v[(k + cell.nv - 1) % cell.nv]] - p;
  const Vec2 en = T * dn, ep = T * dp;
  const double d = en.norm() * ep.norm(), d_phys = dn.norm() * dp.norm();
  sine_T = d > 0 ? cross2(en, ep) / d : -1.0;
  sine_phys = d_phys > 0 ? cross2(dn, dp) / d_phys : -1.0;
}

// The smallest corner sines of the cells around node i (in T and physically), split into the
// corners that moving x_i leaves unchanged (a quad's corner opposite i) and those it changes: a
// guard re-evaluates only the latter (3 of a quad's 4 corners).
struct StarSines {
  double fixed_T = 1e300, fixed_phys = 1e300, moving_T = 1e300, moving_phys = 1e300;
};
StarSines star_sines(const Mesh& m, int i, const std::vector<int>& cells, const Mat2& T, bool moving_only,
                     const StarSines& fixed = {}) {
  StarSines s = fixed;
  for (int c : cells) {
    const Cell& cell = m.cells[c];
    const int n = cell.nv, k = local_index(cell, i);
    for (int j = 0; j < n; ++j) {
      const bool moving = !(n == 4 && j == (k + 2) % 4);
      if (moving_only && !moving) continue;
      double sT, sP;
      corner_sines(m, cell, j, T, sT, sP);
      double& mT = moving ? s.moving_T : s.fixed_T;
      double& mP = moving ? s.moving_phys : s.fixed_phys;
      mT = std::min(mT, sT);
      mP = std::min(mP, sP);
    }
  }
  return s;
}

// The stars of the nodes: cells around each node, the two cells of each edge, the edge
// neighbours of each node (deterministic order) and the fixed nodes (on a free edge, hanging,
// or in no cell).
struct Topology {
  std::vector<char> fixed;
  std::vector<std::vector<int>> node_cells, nbrs;
  std::unordered_map<std::uint64_t, EdgeCells> edges;
  static std::uint64_t key(int a, int b) { return edge_key(a, b); }
  const EdgeCells& edge(int a, int b) const { return edges.at(key(a, b)); }
};

Topology build_topology(const Mesh& m) {
  Topology t;
  const int nn = m.num_nodes();
  t.fixed = boundary_node_flags(m);
  t.node_cells.resize(nn);
  t.nbrs.resize(nn);
  t.edges.reserve(4 * m.cells.size());
  for (int c = 0; c < m.num_cells(); ++c) {
    const Cell& cell = m.cells[c];
    for (int k = 0; k < cell.nv; ++k) {
      t.node_cells[cell.v[k]].push_back(c);
      auto& e = t.edges[Topology::key(cell.v[k], cell.v[(k + 1) % cell.nv])];
      if (e.a < 0) e.a = c;
      else if (e.b < 0) e.b = c;
      else throw InputError("mesh: an edge is shared by more than two cells");
    }
  }
  for (int v = 0; v < nn; ++v) {
    for (int c : t.node_cells[v]) {
      const Cell& cell = m.cells[c];
      int k = local_index(cell, v);
      for (int w : {cell.v[(k + 1) % cell.nv], cell.v[(k + cell.nv - 1) % cell.nv]})
        if (std::find(t.nbrs[v].begin(), t.nbrs[v].end(), w) == t.nbrs[v].end()) t.nbrs[v].push_back(w);
    }
    // A node with an edge that has a single cell is on the boundary (or a hanging node).
    for (int w : t.nbrs[v])
      if (t.edge(v, w).b < 0) t.fixed[v] = 1;
    if (t.node_cells[v].empty()) t.fixed[v] = 1;
  }
  return t;
}

// Moves node i from xi by step, halving it (up to max_halvings times) until every cell around i
// that was valid stays valid and accept(f) holds; restores xi and returns -1 when no trial
// passes, else the number of halvings.
template <class Accept>
int guarded_move(Mesh& m, int i, const Vec2& xi, const Vec2& step, const std::vector<int>& cells,
                 int max_halvings, Accept&& accept) {
  // (a node's star is a handful of cells: no allocation per move unless it is unusually large)
  char small[32];
  std::vector<char> large(cells.size() > sizeof small ? cells.size() : 0);
  char* was_valid = large.empty() ? small : large.data();
  for (size_t k = 0; k < cells.size(); ++k) was_valid[k] = cell_valid(m, m.cells[cells[k]]);
  double f = 1.0;
  for (int h = 0; h <= max_halvings; ++h, f *= 0.5) {
    m.nodes[i] = xi + f * step;
    bool ok = true;
    for (size_t k = 0; k < cells.size() && ok; ++k)
      if (was_valid[k] && !cell_valid(m, m.cells[cells[k]])) ok = false;
    if (ok && accept()) return h;
  }
  m.nodes[i] = xi;
  return -1;
}

// Counts a guarded_move in st (h: its halvings, -1 rejected); returns the length moved, -1 when
// rejected.
double count_move(SmoothStats& st, int h, const Vec2& step) {
  if (h < 0) {
    ++st.moves_rejected;
    return -1;
  }
  (h == 0 ? st.moves_full : st.moves_reduced)++;
  const double d = std::ldexp(1.0, -h) * step.norm();
  st.max_displacement = std::max(st.max_displacement, d);
  return d;
}
// A wall node slides only this far towards its wall neighbours (fraction of the segment a-b).
constexpr double kSlideMin = 0.1;
// A wall node is on a straight wall when its distance from the line of its wall neighbours a, b
// is at most this times |b - a| (rounding only: a polyline approximating a curve turns by much more).
constexpr double kCollinear = 1e-9;
// The shape fit's guard accepts a corner sine this far below its bound (rounding).
constexpr double kSineSlack = 1e-12;

std::vector<WallSlide> wall_slides(const Mesh& m, const Topology& topo) {
  const int nn = m.num_nodes();
  // listed boundary edges per node (group and other end)
  std::vector<std::vector<std::pair<int, int>>> listed(nn);
  for (const BoundaryEdge& e : m.boundary) {
    if (e.v[0] < 0 || e.v[1] < 0 || e.v[0] >= nn || e.v[1] >= nn) continue;
    listed[e.v[0]].emplace_back(e.v[1], e.group);
    listed[e.v[1]].emplace_back(e.v[0], e.group);
  }
  std::vector<WallSlide> out;
  for (int v = 0; v < nn; ++v) {
    if (!topo.fixed[v] || topo.node_cells[v].empty()) continue;
    int ends[2], nf = 0;
    bool ok = true;
    for (int w : topo.nbrs[v])
      if (topo.edge(v, w).b < 0) {
        if (nf == 2) { ok = false; break; }
        ends[nf++] = w;
      }
    if (!ok || nf != 2) continue;
    // the listed edges at v: none, or exactly the two free edges, in one group
    if (!listed[v].empty()) {
      if (listed[v].size() != 2 || listed[v][0].second != listed[v][1].second) continue;
      const int l0 = listed[v][0].first, l1 = listed[v][1].first;
      if (!((l0 == ends[0] && l1 == ends[1]) || (l0 == ends[1] && l1 == ends[0]))) continue;
    }
    // a hanging node: its two free edges lie on a cell edge a-b
    if (topo.edges.count(Topology::key(ends[0], ends[1]))) continue;
    const Vec2 &xa = m.nodes[ends[0]], &xb = m.nodes[ends[1]], &x = m.nodes[v];
    const Vec2 d = xb - xa;
    const double dd = d.squaredNorm();
    if (!(dd > 0)) continue;
    const double lambda = (x - xa).dot(d) / dd;
    if (std::abs(cross2(d, x - xa)) > kCollinear * dd || !(lambda > 0 && lambda < 1)) continue;
    out.push_back({v, ends[0], ends[1]});
  }
  return out;
}

/// The nodes in the order of their distance from the nodes' centroid c, measured in each node's
/// metric, |T_i (x_i - c)| (T_at(i) = T_i), then by x, then y, then the index: the order both
/// smoothings visit (angle_smooth) or colour (shape_smooth) the nodes in. Gauss-Seidel's result
/// depends on the order when the sweeps stop before convergence, and the index order is the
/// file's numbering; this one turns and mirrors with the problem, and in a constant metric T it
/// is the order of the mesh mapped by T. Nodes exactly as far from c as another (a mesh
/// symmetric about c) go by x, then y: a renumbering keeps that, a turn does not.
std::vector<int> distance_order(const Mesh& m, const std::function<Mat2(int)>& T_at) {
  const int nn = m.num_nodes();
  Vec2 centre = Vec2::Zero();
  for (const Vec2& x : m.nodes) centre += x;
  centre /= std::max(nn, 1);
  std::vector<double> dist2(nn);
  std::vector<int> order(nn);
  for (int i = 0; i < nn; ++i) {
    dist2[i] = (T_at(i) * (m.nodes[i] - centre)).squaredNorm();
    order[i] = i;
  }
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    const Vec2 &p = m.nodes[a], &q = m.nodes[b];
    return dist2[a] != dist2[b] ? dist2[a] < dist2[b] : p.x() != q.x() ? p.x() < q.x() : p.y() != q.y() ? p.y() < q.y() : a < b;
  });
  return order;
}

}  // namespace

SmoothStats angle_smooth(Mesh& m, const SmoothOptions& opt, const NodeMetric& metric) {
  SmoothStats st;
  const int nn = m.num_nodes();
  const Topology topo = build_topology(m);
  const std::vector<char>& fixed = topo.fixed;
  const auto& node_cells = topo.node_cells;
  const auto& nbrs = topo.nbrs;
  for (int v = 0; v < nn; ++v) st.interior_nodes += fixed[v] ? 0 : 1;

  st.min_angle_before = quality_summary(m).min_angle_deg;
  // Gauss-Seidel in the nodes' distance order (distance_order), not the file's numbering
  const std::vector<int> order =
      distance_order(m, [&](int i) { return metric ? Mat2(metric(m.nodes[i])) : Mat2(Mat2::Identity()); });
  for (int sweep = 0; sweep < opt.sweeps; ++sweep) {
    double max_rel = 0;
    for (const int i : order) {
      if (fixed[i]) continue;
      const Vec2 xi = m.nodes[i];
      // The step is made in the space mapped by T (T x_i's star), then mapped back.
      const Mat2 T = metric ? metric(xi) : Mat2::Identity();
      const Mat2 Tinv = T.inverse();
      Vec2 sum = Vec2::Zero();
      double size = 0;
      int n = 0;
      for (int j : nbrs[i]) {
        const auto& e = topo.edge(i, j);
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
      const LocalQuality before = cells_quality(m, cells, T);
      const int h = guarded_move(m, i, xi, step, cells, opt.max_halvings, [&] {
        const LocalQuality after = cells_quality(m, cells, T);
        return after.angle >= before.angle && after.sine >= std::min(before.sine, opt.min_sine);
      });
      const double d = count_move(st, h, step);
      if (d < 0) continue;
      max_rel = std::max(max_rel, d / size);
    }
    ++st.sweeps;
    if (max_rel <= opt.tolerance) {
      st.converged = true;
      break;
    }
  }
  st.min_angle_after = quality_summary(m).min_angle_deg;
  return st;
}

std::vector<WallSlide> wall_slides(const Mesh& m) {
  const Topology topo = build_topology(m);
  return wall_slides(m, topo);
}

SmoothStats shape_smooth(Mesh& m, const ShapeSmoothOptions& opt, const NodeMetric& metric) {
  if (!metric) return shape_smooth(m, opt, HintedNodeMetric{});
  return shape_smooth(m, opt, HintedNodeMetric([&](const Vec2& x, int&) { return metric(x); }));
}

SmoothStats shape_smooth(Mesh& m, const ShapeSmoothOptions& opt, const HintedNodeMetric& metric) {
  // the documented ranges, for library callers (the tool checks its flags in lib/cli/option_ranges.cpp)
  if (!(opt.relaxation > 0 && opt.relaxation < 2) || opt.sweeps < 0 || !(opt.target_edge > 0) ||
      !(opt.size_min > 0 && opt.size_min <= opt.size_max) || opt.max_halvings < 0 || !(opt.tolerance >= 0))
    throw InputError("", "ShapeSmoothOptions out of range: relaxation in (0, 2), sweeps >= 0, target_edge > 0, "
                         "0 < size_min <= size_max, max_halvings >= 0, tolerance >= 0");
  SmoothStats st;
  const int nn = m.num_nodes();
  const Topology topo = build_topology(m);
  for (int v = 0; v < nn; ++v) st.interior_nodes += topo.fixed[v] ? 0 : 1;
  // wall nodes that slide along their straight wall (slide[v].a >= 0), when asked
  std::vector<WallSlide> slide(nn);
  if (opt.slide_walls)
    for (const WallSlide& w : wall_slides(m, topo)) {
      slide[w.node] = w;
      ++st.sliding_nodes;
    }
  auto movable = [&](int v) { return !topo.fixed[v] || slide[v].a >= 0; };
  const double lo = opt.size_min * opt.target_edge, hi = opt.size_max * opt.target_edge;
  // ideal corner edges (next, previous), counter-clockwise: a square's and an equilateral triangle's
  const Vec2 quad_e1(0, 1), tri_e1(0.5, std::sqrt(3.0) / 2);
  std::vector<Mat2> node_T(nn, Mat2::Identity()), cell_T(opt.cell_metric ? m.num_cells() : 0, Mat2::Identity());
  // and their Gram matrices T^T T, which every corner term of the fit uses (set with T)
  std::vector<Mat2> node_G(nn, Mat2::Identity()), cell_G(cell_T.size(), Mat2::Identity());
  // the metric lookups' hints: the frame cell each node (cell centroid) was in at the last sweep
  std::vector<int> node_hint(nn, -1), cell_hint(cell_T.size(), -1);
  // nodes to visit in a sweep: all in the first, then those with a cell-mate (or themselves)
  // that moved more than the tolerance in the sweep before (the others' fits are unchanged)
  std::vector<char> active(nn, 1), next(nn, 0);
  st.min_angle_before = quality_summary(m).min_angle_deg;
  // Colours: nodes of one colour share no cell, so within a colour every node's fit and guard
  // read only positions that no other node of that colour writes — the colour's nodes move in
  // parallel and the result does not depend on the thread count (colour by colour, Gauss-Seidel
  // across colours). The colouring is greedy in distance_order (the nodes' metric distance from
  // their centroid): the colours are the Gauss-Seidel order, and greedy in index order they
  // followed the file's node numbering — renumbering the nodes, or turning or mirroring the
  // problem (whose chain numbers the nodes otherwise), moved the fitted nodes by up to 0.036 of
  // the domain after the 30 sweeps (PHiLiP's ss15_adj_p2).
  std::vector<std::vector<int>> colours;
  {
    int hint = -1;
    const std::vector<int> order =
        distance_order(m, [&](int i) { return metric ? Mat2(metric(m.nodes[i], hint)) : Mat2(Mat2::Identity()); });
    std::vector<int> colour(nn, -1), seen(nn, -1);
    for (const int i : order) {
      if (!movable(i)) continue;
      for (int c : topo.node_cells[i])
        for (int k = 0; k < m.cells[c].nv; ++k)
          if (colour[m.cells[c].v[k]] >= 0) seen[colour[m.cells[c].v[k]]] = i;
      int col = 0;
      while (col < nn && seen[col] == i) ++col;
      colour[i] = col;
      if (col >= static_cast<int>(colours.size())) colours.resize(col + 1);
      colours[col].push_back(i);
    }
  }
  // one node's fit and guarded move; marks the nodes to revisit when it moved beyond the tolerance
  auto update = [&](int i, SmoothStats& local, std::vector<int>& marks) {
    const Vec2 xi = m.nodes[i];
    const Mat2& T = node_T[i];
    // normal equations of sum over the corner terms |T_j (x_i - x_ref) - b|^2 in x_i
    Mat2 A = Mat2::Zero();
    Vec2 rhs = Vec2::Zero();
    auto term = [&](const Mat2& Tj, const Mat2& G, const Vec2& xref, const Vec2& b) {
      A += G;
      rhs += G * xref + Tj.transpose() * b;
    };
    double size = 0;
    int nsize = 0;
    for (int c : topo.node_cells[i]) {
      const Cell& cell = m.cells[c];
      const int n = cell.nv, k = local_index(cell, i);
      const Vec2& e1 = n == 3 ? tri_e1 : quad_e1;
      for (int j : {k, (k + n - 1) % n, (k + 1) % n}) {
        // corner j: a0 = T (x_next - x_j), a1 = T (x_prev - x_j); the similarity z (complex)
        // with z e0 ~ a0, z e1 ~ a1, e0 = 1, in the least-squares sense: z = (a0 + conj(e1) a1) / 2
        const Vec2& xj = m.nodes[cell.v[j]];
        const Vec2& xn = m.nodes[cell.v[(j + 1) % n]];
        const Vec2& xp = m.nodes[cell.v[(j + n - 1) % n]];
        const Mat2& Tj = opt.cell_metric ? cell_T[c] : node_T[cell.v[j]];
        const Mat2& Gj = opt.cell_metric ? cell_G[c] : node_G[cell.v[j]];
        const Vec2 a0 = Tj * (xn - xj), a1 = Tj * (xp - xj);
        Vec2 z(0.5 * (a0.x() + e1.x() * a1.x() + e1.y() * a1.y()), 0.5 * (a0.y() + e1.x() * a1.y() - e1.y() * a1.x()));
        const double r = z.norm();
        if (!(r > 0) || !std::isfinite(r)) return;
        z *= std::clamp(r, lo, hi) / r;
        const Vec2 b0 = z, b1(z.x() * e1.x() - z.y() * e1.y(), z.x() * e1.y() + z.y() * e1.x());
        if (j == k) {  // |T_i (x_n - x_i) - b0|^2 + |T_i (x_p - x_i) - b1|^2
          term(Tj, Gj, xn, -b0);
          term(Tj, Gj, xp, -b1);
          size += (xn - xi).norm() + (xp - xi).norm();
          nsize += 2;
        } else if (j == (k + n - 1) % n) {  // i is the next node of corner j: |T_j (x_i - x_j) - b0|^2
          term(Tj, Gj, xj, b0);
        } else {  // i is the previous node of corner j
          term(Tj, Gj, xj, b1);
        }
      }
    }
    if (nsize == 0 || !(A.determinant() > 0)) return;
    Vec2 step;
    if (slide[i].a >= 0) {
      // on its straight wall: x = x_a + lambda (x_b - x_a), the quadratic's minimiser on that line,
      // lambda kept in [kSlideMin, 1 - kSlideMin] (the node stays between its wall neighbours)
      const Vec2 &xa = m.nodes[slide[i].a], d = m.nodes[slide[i].b] - xa;
      const double dAd = d.dot(A * d);
      if (!(dAd > 0)) return;
      const double lambda = std::clamp(d.dot(rhs - A * xa) / dAd, kSlideMin, 1 - kSlideMin);
      step = xa + lambda * d - xi;
    } else {
      step = opt.relaxation * (A.inverse() * rhs - xi);
    }
    if (!(step.norm() > 0) || !std::isfinite(step.x()) || !std::isfinite(step.y())) return;
    const auto& cells = topo.node_cells[i];
    // the guard: no corner sine of the star (in the metric, and physically) falls below the
    // smaller of its smallest before the move and the bound; the corners opposite i are taken once
    StarSines fixed = star_sines(m, i, cells, T, false);
    const double before = std::min(fixed.fixed_T, fixed.moving_T), before_phys = std::min(fixed.fixed_phys, fixed.moving_phys);
    fixed.moving_T = fixed.moving_phys = 1e300;
    // (kSineSlack: a wall node sliding along its wall leaves its neighbours' corners on the wall
    // unchanged but for rounding; without the slack rounding alone would decide such a move)
    const int h = guarded_move(m, i, xi, step, cells, opt.max_halvings, [&] {
      const StarSines after = star_sines(m, i, cells, T, true, fixed);
      return std::min(after.fixed_T, after.moving_T) >= std::min(before, opt.min_sine) - kSineSlack &&
             std::min(after.fixed_phys, after.moving_phys) >= std::min(before_phys, opt.min_sine_physical) - kSineSlack;
    });
    const double d = count_move(local, h, step);
    if (d < 0) return;
    if (d > opt.tolerance * (size / nsize))
      for (int c : cells)
        for (int k = 0; k < m.cells[c].nv; ++k) marks.push_back(m.cells[c].v[k]);
  };
  for (int sweep = 0; sweep < opt.sweeps; ++sweep) {
    bool any = false;
    if (metric) {  // each corner is fitted in the metric at its own node, or its cell's centroid (frozen for the sweep)
#pragma omp parallel for schedule(static)
      for (int v = 0; v < nn; ++v)
        if (!topo.node_cells[v].empty()) {
          node_T[v] = metric(m.nodes[v], node_hint[v]);
          node_G[v] = node_T[v].transpose() * node_T[v];
        }
      if (opt.cell_metric) {
#pragma omp parallel for schedule(static)
        for (int c = 0; c < m.num_cells(); ++c) {
          cell_T[c] = metric(cell_centroid(m, c), cell_hint[c]);
          cell_G[c] = cell_T[c].transpose() * cell_T[c];
        }
      }
    }
    for (const std::vector<int>& nodes : colours) {
      const int nc = static_cast<int>(nodes.size());
#pragma omp parallel if (nc >= 2048)
      {
        SmoothStats local;
        std::vector<int> marks;
#pragma omp for schedule(static) nowait
        for (int q = 0; q < nc; ++q)
          if (active[nodes[q]]) update(nodes[q], local, marks);
#pragma omp critical(shape_smooth_merge)
        {  // sums, a maximum and flags: the same in any merge order
          st.moves_full += local.moves_full;
          st.moves_reduced += local.moves_reduced;
          st.moves_rejected += local.moves_rejected;
          st.max_displacement = std::max(st.max_displacement, local.max_displacement);
          for (int v : marks) next[v] = 1;
          any = any || !marks.empty();
        }
      }
    }
    ++st.sweeps;
    if (!any) {
      st.converged = true;
      break;
    }
    active.swap(next);
    std::fill(next.begin(), next.end(), 0);
  }
  st.min_angle_after = quality_summary(m).min_angle_deg;
  return st;
}

}  // namespace quadapt
