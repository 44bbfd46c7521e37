#include "lpcvt/lattice.hpp"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <deque>

namespace quadapt::lpcvt {

namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using DT = CGAL::Delaunay_triangulation_2<K>;
using Point = K::Point_2;
using VH = DT::Vertex_handle;
}  // namespace

Vec2 lattice_seed(const Background& bg) {
  const Vec2 mid = 0.5 * (bg.lo() + bg.hi());
  Vec2 best = mid;
  double bd = 1e300;
  for (int q = 0; q < bg.num_cells(); ++q) {
    const IntegrationCell& c = bg.cell(q);
    Vec2 g = Vec2::Zero();
    for (int k = 0; k < c.nv; ++k) g += c.v[k] / c.nv;
    const double d = (g - mid).squaredNorm();
    if (d < bd) {
      bd = d;
      best = g;
    }
  }
  if (bg.inside(mid)) return mid;
  return best;
}

std::vector<Vec2> lattice_points(const Background& bg, const std::vector<Vec2>& fixed, const Vec2& seed,
                                 double delta, int max_points) {
  std::vector<Vec2> out;
  DT dt;
  VH hint;
  for (const Vec2& p : fixed) hint = dt.insert(Point(p.x(), p.y()), hint != VH() ? hint->face() : DT::Face_handle());
  std::vector<VH> visited;
  // True when a point lies within metric distance delta of y (metric M at y).
  auto crowded = [&](const Vec2& y, const Mat2& M, double R, VH near_hint) -> bool {
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
  struct Item {
    Vec2 p;
    int cell;
    VH vh;
  };
  std::deque<Item> queue;
  const int c0 = bg.locate(seed);
  if (c0 < 0) return out;
  {
    const Mat2 M = bg.metric(c0, seed);
    const double R = delta * M.inverse().norm();
    if (!crowded(seed, M, R, hint)) {
      hint = dt.insert(Point(seed.x(), seed.y()), hint != VH() ? hint->face() : DT::Face_handle());
      out.push_back(seed);
      queue.push_back({seed, c0, hint});
    }
  }
  while (!queue.empty() && static_cast<int>(out.size()) < max_points) {
    const Item it = queue.front();
    queue.pop_front();
    const Mat2 V = bg.metric(it.cell, it.p).inverse();
    const Vec2 a = V.col(0), b = V.col(1);
    for (const Vec2& y : {Vec2(it.p + a), Vec2(it.p + b), Vec2(it.p - a), Vec2(it.p - b)}) {
      const int c = bg.locate(y, it.cell);
      if (c < 0) continue;
      const Mat2 M = bg.metric(c, y);
      // Euclidean radius of the metric ball of radius delta: delta * largest singular value of M^-1
      const double R = delta * M.inverse().norm();
      if (crowded(y, M, R, it.vh)) continue;
      VH vh = dt.insert(Point(y.x(), y.y()), it.vh->face());
      out.push_back(y);
      queue.push_back({y, c, vh});
      if (static_cast<int>(out.size()) >= max_points) break;
    }
  }
  return out;
}

}  // namespace quadapt::lpcvt
