// Voronoi cells in the frame's metric (lpcvt/metric_graph.hpp, issue #14): the metric in-circle
// test, the flipped graph, the pieces (tiling, nearest in G_Q), the gradient against finite
// differences, and the lattice seed's registration with the boundary.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

#include <omp.h>

#include "helpers.hpp"
#include "lpcvt/boundary_points.hpp"
#include "lpcvt/energy.hpp"
#include "lpcvt/lattice.hpp"
#include "lpcvt/metric_graph.hpp"
#include "lpcvt/rvd.hpp"
#include "lpcvt/site_tree.hpp"

using namespace lpcvt_test;

namespace {

/// The sites of `list` (indices into x) inside the box c +- e, in the list's order.
std::vector<int> in_box(const std::vector<Vec2>& x, const std::vector<int>& list, const Vec2& c, const Vec2& e) {
  std::vector<int> out;
  for (int i : list)
    if (std::abs(x[i].x() - c.x()) <= e.x() && std::abs(x[i].y() - c.y()) <= e.y()) out.push_back(i);
  return out;
}

/// All sites of x inside the box c +- e, ascending (the brute-force answer).
std::vector<int> in_box(const std::vector<Vec2>& x, const Vec2& c, const Vec2& e) {
  std::vector<int> all(x.size());
  for (size_t i = 0; i < x.size(); ++i) all[i] = static_cast<int>(i);
  return in_box(x, all, c, e);
}

/// The edges of the triangles, each once as (smaller, larger) site, sorted.
std::vector<std::array<int, 2>> edges(const std::vector<std::array<int, 3>>& tris) {
  std::vector<std::array<int, 2>> e;
  for (auto t : tris)
    for (int k = 0; k < 3; ++k) e.push_back({std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])});
  std::sort(e.begin(), e.end());
  e.erase(std::unique(e.begin(), e.end()), e.end());
  return e;
}

double area_of(const std::vector<Vec2>& v) {
  double a = 0;
  for (size_t k = 0; k < v.size(); ++k) {
    const Vec2 &p = v[k], &q = v[(k + 1) % v.size()];
    a += p.x() * q.y() - p.y() * q.x();
  }
  return 0.5 * a;
}

}  // namespace

TEST_CASE("metric in-circle: invariant under the map, sign as the Euclidean test in the mapped plane") {
  const Mat2 M = rotated_metric(0.5, 0.05, 0.7);
  const Mat2 Minv = M.inverse();
  // the unit square's corners in the mapped plane are co-circular; its centre is inside
  const Vec2 a = Minv * Vec2(0, 0), b = Minv * Vec2(1, 0), c = Minv * Vec2(1, 1), d = Minv * Vec2(0, 1);
  CHECK(std::abs(metric_incircle(M, a, b, c, d)) < 1e-12);
  CHECK(metric_incircle(M, a, b, c, Minv * Vec2(0.5, 0.5)) > 0.1);
  CHECK(metric_incircle(M, a, b, c, Minv * Vec2(2, 2)) < -0.1);
  // a point inside the Euclidean circle of (a, b, c) but outside the metric one: the tests differ
  const Mat2 I = Mat2::Identity();
  const Vec2 far = Minv * Vec2(0.5, 1.3);
  CHECK(metric_incircle(M, a, b, c, far) < 0);
  (void)I;
}

TEST_CASE("metric in-circle: a reflected M (det M < 0, same M^T M) gives the same answer") {
  // most of PHiLiP's frames store a reflected M; the test must depend on the metric only
  const Mat2 M = rotated_metric(0.2, 0.02, 0.5);
  Mat2 R = Mat2::Identity();
  R(1, 1) = -1;
  const Mat2 Mr = R * M;  // (R M)^T (R M) = M^T M
  REQUIRE(Mr(0, 0) * Mr(1, 1) - Mr(0, 1) * Mr(1, 0) < 0);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(0, 1);
  int inside = 0, outside = 0;
  for (int k = 0; k < 200; ++k) {
    Vec2 a(U(rng), U(rng)), b(U(rng), U(rng)), c(U(rng), U(rng)), d(U(rng), U(rng));
    if ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x() < 0) std::swap(b, c);
    const double t = metric_incircle(M, a, b, c, d), tr = metric_incircle(Mr, a, b, c, d);
    CHECK(tr == doctest::Approx(t).epsilon(1e-9));
    (t > 0 ? inside : outside)++;
  }
  CHECK(inside > 10);
  CHECK(outside > 10);
}

TEST_CASE("metric flips give the Delaunay triangulation of the mapped points (constant metric)") {
  const Mat2 M = rotated_metric(0.2, 0.02, 0.5);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> U(0, 1);
  std::vector<Vec2> x;
  for (int i = 0; i < 300; ++i) x.emplace_back(U(rng), U(rng));
  DelaunayGraph dt(x, true, false);
  MetricGraph g = metric_delaunay(x, dt.triangles(), [&](const std::array<Vec2, 4>&) { return M; });
  CHECK(g.flips > 0);
  CHECK_FALSE(g.capped);
  // every interior edge is locally Delaunay in the metric: the empty-circle test holds for
  // every triangle against every vertex (exhaustive: 300 points)
  std::vector<Vec2> y(x.size());
  for (size_t i = 0; i < x.size(); ++i) y[i] = M * x[i];
  DelaunayGraph mapped(y, true, false);
  CHECK(edges(g.tris) == edges(mapped.triangles()));
  // without the flips the graphs differ (the test can fail)
  CHECK(edges(dt.triangles()) != edges(mapped.triangles()));
}

TEST_CASE("metric flips at 1000:1: the mapped points' Delaunay triangulation, past the old cap of 20 per site") {
  // a constant 1000:1 metric at 30 degrees (lpcvt's M_eff of the frame h1 = 0.2, h2 = 2e-4) and
  // the unit square's wall points one metric unit apart, which is all that frame's sites are: from
  // the Euclidean triangulation (fans across the square) the flips need more than 20 per site;
  // stopped there (the cap before kMaxFlipsPerSite) the graph kept long Euclidean edges (lpcvt's
  // output: median largest metric angle 179.8 degrees)
  const Mat2 M = rotated_metric(0.8, 0.0008, 0.5236);
  std::vector<Vec2> x;
  const Vec2 corner[4] = {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)};
  for (int side = 0; side < 4; ++side) {
    const Vec2 a = corner[side], b = corner[(side + 1) % 4];
    const int n = static_cast<int>(std::ceil((M * (b - a)).norm()));
    for (int k = 0; k < n; ++k) x.push_back(a + (b - a) * (k / double(n)));
  }
  DelaunayGraph dt(x, true, false);
  MetricGraph g = metric_delaunay(x, dt.triangles(), [&](const std::array<Vec2, 4>&) { return M; });
  CHECK_FALSE(g.capped);
  CHECK(g.flips > 20 * static_cast<long>(x.size()));  // the old cap would have stopped them
  // every edge locally Delaunay in the metric (the walls' points make co-circular trapezoids, so
  // the triangulation is one of several Delaunay ones: not compared edge by edge)
  auto not_delaunay = [&](const std::vector<std::array<int, 3>>& tris) {
    std::map<std::pair<int, int>, int> opposite;  // directed edge a -> b: the third vertex
    for (const auto& t : tris)
      for (int k = 0; k < 3; ++k) opposite[{t[k], t[(k + 1) % 3]}] = t[(k + 2) % 3];
    int bad = 0;
    for (const auto& [e, c] : opposite) {
      auto it = opposite.find({e.second, e.first});
      if (it != opposite.end() && metric_incircle(M, x[e.first], x[e.second], x[c], x[it->second]) > 1e-9) ++bad;
    }
    return bad;
  };
  CHECK(not_delaunay(g.tris) == 0);
  CHECK(not_delaunay(dt.triangles()) > 1000);  // the test can fail
}

TEST_CASE("metric flips terminate with a discontinuous metric (no flip cycles)") {
  // a checkerboard of two strongly anisotropic metrics 85 degrees apart: Lawson's flips have no
  // decreasing potential here; without the rule "an edge removed is never made again" the flips
  // cycle until the cap (20 per site)
  const Mat2 A = rotated_metric(0.2, 0.01, 0.3), B = rotated_metric(0.2, 0.01, 1.78);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(0, 1);
  std::vector<Vec2> x;
  for (int i = 0; i < 600; ++i) x.emplace_back(U(rng), U(rng));
  DelaunayGraph dt(x, true, false);
  auto metric = [&](const std::array<Vec2, 4>& q) {
    const Vec2 c = 0.25 * (q[0] + q[1] + q[2] + q[3]);
    const int i = static_cast<int>(std::floor(c.x() / 0.1)), j = static_cast<int>(std::floor(c.y() / 0.1));
    return (i + j) % 2 == 0 ? A : B;
  };
  MetricGraph g = metric_delaunay(x, dt.triangles(), metric);
  CHECK_FALSE(g.capped);
  CHECK(g.flips > 100);
  CHECK(g.flips < 6 * static_cast<long>(x.size()));
  // still a triangulation: every triangle counter-clockwise, total area that of the hull
  double area = 0;
  for (const auto& t : g.tris) {
    const double a = 0.5 * ((x[t[1]] - x[t[0]]).x() * (x[t[2]] - x[t[0]]).y() -
                            (x[t[1]] - x[t[0]]).y() * (x[t[2]] - x[t[0]]).x());
    CHECK(a > 0);
    area += a;
  }
  double hull = 0;
  for (const auto& t : dt.triangles())
    hull += 0.5 * ((x[t[1]] - x[t[0]]).x() * (x[t[2]] - x[t[0]]).y() - (x[t[1]] - x[t[0]]).y() * (x[t[2]] - x[t[0]]).x());
  CHECK(area == doctest::Approx(hull).epsilon(1e-12));
}

TEST_CASE("metric pieces tile the domain, and each lies nearest its own site in G_Q") {
  for (int kind = 0; kind < 3; ++kind) {
    Mesh m = kind == 0 ? saddle_square(5) : kind == 1 ? l_shape() : square_with_hole();
    set_frame(m, 0.4, 0.08, 0.6);
    Background bg = Background::from_frame(m, 1.0, "mem");
    bg.set_metric_cells(true);
    int nfixed = 0;
    auto x = boundary_and_random(bg, 60, 3 + kind, nfixed);
    RestrictedVoronoi rvd(bg, x);
    double total = 0;
    int wrong = 0;
    for (const auto& p : rvd.all_pieces()) {
      total += area_of(p.v);
      const Mat2 G = bg.partition_metric(p.cell);
      Vec2 z = Vec2::Zero();
      for (auto& v : p.v) z += v / p.v.size();
      const double di = (z - x[p.site]).dot(G * (z - x[p.site]));
      for (size_t j = 0; j < x.size(); ++j)
        if ((z - x[j]).dot(G * (z - x[j])) < di - 1e-12) ++wrong;
    }
    CHECK(total == doctest::Approx(bg.area()).epsilon(1e-12));
    CHECK(wrong == 0);
  }
}

TEST_CASE("metric cells: gradient matches central finite differences") {
  for (int kind = 0; kind < 2; ++kind) {
    Mesh m = kind == 0 ? saddle_square(4) : l_shape();
    set_frame(m, 0.3, 0.06, 0.5 + kind);
    Background bg = Background::from_frame(m, 1.0, "mem");
    bg.set_metric_cells(true);
    int nfixed = 0;
    auto x = boundary_and_random(bg, 25, 9 + kind, nfixed);
    const double worst = fd_worst(bg, x, nfixed, 1e-6 * std::sqrt(bg.area()));
    MESSAGE("metric cells, max relative FD error " << worst);
    CHECK(worst < 1e-5);
  }
}

TEST_CASE("metric cells: gradient matches finite differences with a discontinuous (16x16 sampled) metric") {
  Mesh m = saddle_square(16);
  SaddleMetric f;
  Background bg = Background::sampled(m, f, 3.0);
  bg.set_metric_cells(true);
  int nfixed = 0;
  auto x = boundary_and_random(bg, 40, 5, nfixed);
  const double worst = fd_worst(bg, x, nfixed, 1e-6);
  MESSAGE("metric cells, sampled metric: max relative FD error " << worst);
  CHECK(worst < 1e-5);
}

TEST_CASE("lattice seed registration: in phase with an aligned boundary, unchanged by an oblique one") {
  const Mat2 M = rotated_metric(0.2, 0.02, 0.0);
  // boundary points of the unit square at the lattice spacing (aligned)
  std::vector<Vec2> fixed;
  for (int k = 0; k <= 50; ++k) fixed.emplace_back(0, 0.02 * k);
  for (int k = 0; k <= 5; ++k) fixed.emplace_back(0.2 * k, 0);
  const Vec2 y(0.03125, 0.03125);
  const Vec2 r = register_seed(y, M, fixed, 12.0);
  const Vec2 phase = M * r;
  CHECK(std::abs(phase.x() - std::round(phase.x())) < 1e-9);
  CHECK(std::abs(phase.y() - std::round(phase.y())) < 1e-9);
  CHECK((r - y).norm() < 0.2);
  // points spread evenly over all phases: no shift
  std::vector<Vec2> spread;
  for (int k = 0; k < 40; ++k) spread.emplace_back(0.2 * (k / 40.0), 0.02 * ((k * 7 % 40) / 40.0));
  CHECK((register_seed(y, M, spread, 1e9) - y).norm() < 1e-12);
}

TEST_CASE("site tree: a box query lists its sites in one fixed order, a larger box's filtered list is the same") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Vec2> x(3000);
  for (auto& p : x) p = Vec2(u(rng), u(rng) * u(rng));  // denser towards y = 0
  SiteTree tree(x);
  for (int k = 0; k < 200; ++k) {
    const Vec2 c(u(rng), 0.3 * u(rng)), e(0.05 * u(rng), 0.02 * u(rng));
    std::vector<int> small, big;
    tree.query(c - e, c + e, small);
    tree.query(c - 1.7 * e, c + 1.7 * e, big);
    CHECK(in_box(x, big, c, e) == small);
    std::sort(small.begin(), small.end());
    CHECK(small == in_box(x, c, e));
  }
}

TEST_CASE("site tree: built in parallel (subtrees as tasks), the same answers for 1 and 2 threads") {
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Vec2> x(60000);  // above the task threshold (16,384 sites) at the top two levels
  for (auto& p : x) p = Vec2(u(rng), u(rng) * u(rng));
  SiteTree one, two;
  {
    const RestoreThreads restore;
    omp_set_num_threads(1);
    one = SiteTree(x);
    omp_set_num_threads(2);
    two = SiteTree(x);
  }
  for (int k = 0; k < 100; ++k) {
    const Vec2 c(u(rng), 0.3 * u(rng)), e(0.02 * u(rng), 0.01 * u(rng));
    std::vector<int> a, b;
    one.query(c - e, c + e, a);
    two.query(c - e, c + e, b);
    CHECK(a == b);  // same sites in the same (pre-)order
    std::sort(a.begin(), a.end());
    CHECK(a == in_box(x, c, e));
  }
}

TEST_CASE("site tree: refitted to moved sites, the queries stay exact and keep the tree's fixed order") {
  // A minimisation refits the last evaluation's tree (SiteTree::refit). The moves here go from
  // a fraction of the spacing to the whole square, so halves of a split overlap: a query that
  // pruned by the build-time split coordinates (not the refitted bounds) misses sites.
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Vec2> x(5000);
  for (auto& p : x) p = Vec2(u(rng), u(rng) * u(rng));
  SiteTree tree(x);
  {  // refitted to the same sites: the answers of a fresh build, in the same order
    tree.refit(x);
    const SiteTree fresh(x);
    for (int k = 0; k < 50; ++k) {
      const Vec2 c(u(rng), 0.3 * u(rng)), e(0.05 * u(rng), 0.02 * u(rng));
      std::vector<int> a, b;
      tree.query(c - e, c + e, a);
      fresh.query(c - e, c + e, b);
      CHECK(a == b);
    }
  }
  for (const double move : {0.002, 0.02, 0.3, 1.0}) {
    for (auto& p : x) p += move * Vec2(u(rng) - 0.5, u(rng) - 0.5);
    tree.refit(x);
    for (int k = 0; k < 100; ++k) {
      const Vec2 c(u(rng), 0.3 * u(rng)), e(0.05 * u(rng), 0.02 * u(rng));
      std::vector<int> small, big;
      tree.query(c - e, c + e, small);
      tree.query(c - 1.7 * e, c + 1.7 * e, big);
      CHECK(in_box(x, big, c, e) == small);  // one fixed order, whatever the box
      std::sort(small.begin(), small.end());
      CHECK(small == in_box(x, c, e));
    }
  }
}

TEST_CASE("site tree: refitted in parallel, the same answers for 1 and 2 threads") {
  std::mt19937 rng(14);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Vec2> x(60000);  // the refit's top subtrees are tasks from 16,384 sites on
  for (auto& p : x) p = Vec2(u(rng), u(rng));
  SiteTree one(x), two(x);
  for (auto& p : x) p += 0.01 * Vec2(u(rng) - 0.5, u(rng) - 0.5);
  {
    const RestoreThreads restore;
    omp_set_num_threads(1);
    one.refit(x);
    omp_set_num_threads(2);
    two.refit(x);
  }
  for (int k = 0; k < 100; ++k) {
    const Vec2 c(u(rng), u(rng)), e(0.02 * u(rng), 0.02 * u(rng));
    std::vector<int> a, b;
    one.query(c - e, c + e, a);
    two.query(c - e, c + e, b);
    CHECK(a == b);
    std::sort(a.begin(), a.end());
    CHECK(a == in_box(x, c, e));
  }
}

TEST_CASE("metric pieces: the cached security boxes give the pieces of fresh site-tree queries, bit for bit") {
  // a graded frame (sizes 4x apart across the square, 5:1, rotating): a site's pieces in
  // neighbouring cells reuse its box (box_hits), which must change nothing
  Background bg = graded_metric_background();
  int nfixed = 0;
  auto x = boundary_and_random(bg, 1500, 21, nfixed);
  RestrictedVoronoi rvd(bg, x);
  RvdWorkspace shared;
  const std::vector<RvdPiece> cached = rvd.all_pieces(&shared);
  CHECK(shared.box_hits > shared.box_queries / 4);  // the cache is used
  std::vector<RvdPiece> fresh, tmp;
  for (int q = 0; q < bg.num_cells(); ++q) {
    RvdWorkspace ws;  // a new workspace per cell: no site's box is reused across cells
    const int n = rvd.pieces(q, tmp, ws);
    CHECK(ws.box_hits == 0);
    for (int k = 0; k < n; ++k) fresh.push_back(tmp[k]);
  }
  REQUIRE(fresh.size() == cached.size());
  int differ = 0;
  for (size_t k = 0; k < fresh.size(); ++k)
    differ += fresh[k].site != cached[k].site || fresh[k].v != cached[k].v || fresh[k].label != cached[k].label;
  CHECK(differ == 0);
}
