#include "lpcvt/lattice.hpp"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cmath>
#include <queue>
#include <limits>
#include <tuple>

namespace quadapt::lpcvt {

namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using DT = CGAL::Delaunay_triangulation_2<K>;
using Point = K::Point_2;
using VH = DT::Vertex_handle;
}  // namespace

Vec2 register_seed(const Vec2& y, const Mat2& M, const std::vector<Vec2>& fixed, double radius,
                   const Vec2& phase, bool* registered) {
  // phases phi = frac(M (b - y)) of the fixed points b within metric distance `radius`; their
  // circular mean per axis, weighted by the resultant length (a boundary that is not aligned
  // with the lattice gives uniformly spread phases and no shift)
  constexpr double two_pi = 6.283185307179586;
  double c[2] = {0, 0}, s[2] = {0, 0};
  int n = 0;
  for (const Vec2& b : fixed) {
    const Vec2 u = M * (b - y);
    if (u.norm() > radius) continue;
    for (int a = 0; a < 2; ++a) {
      c[a] += std::cos(two_pi * u[a]);
      s[a] += std::sin(two_pi * u[a]);
    }
    ++n;
  }
  Vec2 shift;
  for (int a = 0; a < 2; ++a) {
    const double r = n ? std::hypot(c[a], s[a]) / n : 0.0;  // 1: all in phase, ~0: no preferred phase
    const bool reg = r > 0.5;
    shift[a] = reg ? std::atan2(s[a], c[a]) / two_pi : phase[a];
    if (registered) registered[a] = reg;
  }
  if (shift == Vec2::Zero()) return y;
  return y + M.inverse() * shift;
}

std::vector<Vec2> lattice_points(const Background& bg, const std::vector<Vec2>& fixed, double delta,
                                 int max_points, const Vec2& phase) {
  std::vector<Vec2> out;
  DT dt;
  VH hint;
  for (const Vec2& p : fixed) hint = dt.insert(Point(p.x(), p.y()), hint != VH() ? hint->face() : DT::Face_handle());
  std::vector<VH> visited;
  // True when a point lies within metric distance delta of y (metric M at y).
  auto crowded = [&](const Vec2& y, const Mat2& M, double R, VH near_hint, double delta) -> bool {
    if (dt.number_of_vertices() == 0) return false;
    const Point py(y.x(), y.y());
    VH v0 = dt.nearest_vertex(py, near_hint != VH() ? near_hint->face() : DT::Face_handle());
    auto dist2 = [&](VH v) { return (Vec2(v->point().x(), v->point().y()) - y).squaredNorm(); };
    if (dist2(v0) > R * R) return false;
    visited.clear();
    visited.push_back(v0);
    for (size_t h = 0; h < visited.size(); ++h) {
      VH v = visited[h];
      const Vec2 q(v->point().x(), v->point().y());
      if ((M * (q - y)).norm() < delta) return true;
      auto c = dt.incident_vertices(v), done = c;
      if (c == nullptr) continue;
      do {
        if (dt.is_infinite(c)) continue;
        VH w = c;
        if (dist2(w) > R * R) continue;
        bool seen = false;
        for (VH u : visited)
          if (u == w) {
            seen = true;
            break;
          }
        if (!seen) visited.push_back(w);
      } while (++c != done);
      if (visited.size() > 400) break;  // safety: a pathological metric
    }
    return false;
  };
  // Proposals wait in a priority queue: ring (lattice steps from the seed) first, then the
  // Euclidean distance from the seed, then the order they were made in. Both keys turn and
  // mirror with the problem, so a conflict between two proposals (where the frame grades, two
  // parents propose nearly the same point) is decided the same way in a turned or mirrored
  // frame; the order the four neighbours are proposed in (+a, +b, -a, -b, V's columns, whose
  // signs a mirror's canonical frame flips) decides only exact ties.
  struct Item {
    int ring;
    double dist2;
    long order;
    Vec2 p;
    int cell;
    VH parent;
  };
  auto later = [](const Item& x, const Item& y) {
    return std::tie(x.ring, x.dist2, x.order) > std::tie(y.ring, y.dist2, y.order);
  };
  std::priority_queue<Item, std::vector<Item>, decltype(later)> queue(later);
  long made = 0;
  Vec2 seed = Vec2::Zero();
  // the four lattice neighbours of an accepted point p (V at p) that lie in the domain
  auto propose = [&](const Vec2& p, int cell, VH vh, int ring) {
    const Mat2 V = bg.metric(cell, p).inverse();
    const Vec2 a = V.col(0), b = V.col(1);
    for (const Vec2& y : {Vec2(p + a), Vec2(p + b), Vec2(p - a), Vec2(p - b)}) {
      const int c = bg.locate(y, cell);
      if (c < 0) continue;
      queue.push({ring, (y - seed).squaredNorm(), made++, y, c, vh});
    }
  };
  // Seeds: integration cells' centroids, finest metric first. Ties (a constant frame: every
  // cell) go to the smallest coordinates along the cell's own frame axes (v, then w), so a
  // rotated or mirrored problem picks the mapped seed — not the first cell in the background's
  // order, which does not turn with the problem (tests/cli/loop_rotation.sh). Both keys are
  // rounded (relative 1e-9 of |det M|, 1e-9 of the domain's width) so that the rounding of a
  // turned frame does not decide. The cell index breaks what is left.
  double width = 0;
  {
    Vec2 lo = Vec2::Constant(std::numeric_limits<double>::max()), hi = -lo;
    for (int q = 0; q < bg.num_cells(); ++q)
      for (int k = 0; k < bg.cell(q).nv; ++k) {
        lo = lo.cwiseMin(bg.cell(q).v[k]);
        hi = hi.cwiseMax(bg.cell(q).v[k]);
      }
    width = std::max((hi - lo).norm(), 1e-300);
  }
  auto rounded = [](double x, double unit) { return std::round(x / unit); };
  std::vector<std::tuple<double, double, double, int>> order;
  for (int q = 0; q < bg.num_cells(); ++q) {
    const IntegrationCell& ic = bg.cell(q);
    Vec2 y = Vec2::Zero();
    for (int k = 0; k < ic.nv; ++k) y += ic.v[k] / ic.nv;
    const Mat2 V = ic.M.inverse();
    const Vec2 v = V.col(0).normalized(), w = V.col(1).normalized();
    order.emplace_back(-rounded(std::log(std::abs(ic.M.determinant())), 1e-9), rounded(y.dot(v), 1e-9 * width),
                       rounded(y.dot(w), 1e-9 * width), q);
  }
  std::sort(order.begin(), order.end());
  size_t next_seed = 0;
  while (static_cast<int>(out.size()) < max_points) {
    if (queue.empty()) {
      // the next seed that is not crowded
      bool found = false;
      while (next_seed < order.size() && !found) {
        const int q = std::get<3>(order[next_seed++]);
        const IntegrationCell& ic = bg.cell(q);
        Vec2 y = Vec2::Zero();
        for (int k = 0; k < ic.nv; ++k) y += ic.v[k] / ic.nv;
        Mat2 M = bg.metric(q, y);
        // in phase with the boundary points where they lie on the lattice (e.g. a wall along
        // the frame): otherwise rows start half a spacing off the boundary's and the
        // minimisation leaves a dislocation where they meet
        const Vec2 yr = register_seed(y, M, fixed, 12.0, phase);
        if (bg.locate(yr, q) >= 0) {
          y = yr;
          M = bg.metric(bg.locate(y, q), y);
        }
        const double ds = std::max(1.0, delta);  // a new seed keeps a whole unit off
        const double R = ds * M.inverse().norm();
        if (crowded(y, M, R, hint, ds)) continue;
        hint = dt.insert(Point(y.x(), y.y()), hint != VH() ? hint->face() : DT::Face_handle());
        out.push_back(y);
        seed = y;
        propose(y, q, hint, 1);
        found = true;
      }
      if (!found) break;
      continue;
    }
    const Item it = queue.top();
    queue.pop();
    const Mat2 M = bg.metric(it.cell, it.p);
    // Euclidean radius of the metric ball of radius delta: delta * |M^-1| (Frobenius, >= the
    // largest singular value)
    const double R = delta * M.inverse().norm();
    if (crowded(it.p, M, R, it.parent, delta)) continue;
    VH vh = dt.insert(Point(it.p.x(), it.p.y()), it.parent->face());
    hint = vh;
    out.push_back(it.p);
    propose(it.p, it.cell, vh, it.ring + 1);
  }
  return out;
}

}  // namespace quadapt::lpcvt
