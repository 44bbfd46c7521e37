// The metric graph carried between energy evaluations (lpcvt/metric_graph.hpp,
// metric_delaunay_update; energy.hpp's carry_metric_graph): the same graph as a rebuild where the
// flip rule has one answer, a refusal (nothing changed) when a triangle would invert, and the
// same energy and gradient (to rounding) as with the graph rebuilt at every evaluation.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include <omp.h>

#include "helpers.hpp"
#include "lpcvt/delaunay.hpp"
#include "lpcvt/energy.hpp"
#include "lpcvt/metric_graph.hpp"
#include "lpcvt/rvd.hpp"
#include "../worst.hpp"

using namespace lpcvt_test;

namespace {

/// 300 random points in the unit square and its 4 corners (first; they never move).
std::vector<Vec2> square_points(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(0, 1);
  std::vector<Vec2> x = {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)};
  for (int i = 0; i < 300; ++i) x.emplace_back(U(rng), U(rng));
  return x;
}

MetricGraph rebuilt(const std::vector<Vec2>& x, const Mat2& M) {
  DelaunayGraph dt(x, true, false);
  return metric_delaunay(x, dt.triangles(), [&](const std::array<Vec2, 4>&) { return M; });
}

}  // namespace

TEST_CASE("carried metric graph: after a random move, the graph a rebuild gives (constant metric)") {
  const Mat2 M = rotated_metric(0.2, 0.02, 0.5);
  const std::vector<Vec2> x0 = square_points(5);
  const MetricGraph g0 = rebuilt(x0, M);
  // every interior site moved at random by up to `scale`; the largest scale (halved from a
  // fifth of the mean spacing) at which no triangle inverts
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> U(-1, 1);
  std::vector<Vec2> dir(x0.size(), Vec2::Zero());
  for (size_t i = 4; i < x0.size(); ++i) dir[i] = Vec2(U(rng), U(rng));
  double scale = 0.2 / std::sqrt(300.0);
  MetricGraph g;
  std::vector<Vec2> x1;
  bool ok = false;
  for (int k = 0; k < 20 && !ok; ++k, scale /= 2) {
    x1 = x0;
    for (size_t i = 0; i < x0.size(); ++i) x1[i] += scale * dir[i];
    g = g0;
    ok = metric_delaunay_update(x1, g, [&](const std::array<Vec2, 4>&) { return M; });
  }
  REQUIRE(ok);
  CHECK(g.flips > 0);  // the move changed the graph
  const MetricGraph g1 = rebuilt(x1, M);
  CHECK(g.ptr == g1.ptr);
  CHECK(g.adj == g1.adj);
  CHECK(g.adj != g0.adj);  // without the flips the graphs differ (the test can fail)
  // and the carried graph carries on: a second move, flipped again, is again the rebuild's
  std::vector<Vec2> x2 = x1;
  for (size_t i = 4; i < x0.size(); ++i) x2[i] += 0.5 * scale * Vec2(dir[i].y(), -dir[i].x());
  if (metric_delaunay_update(x2, g, [&](const std::array<Vec2, 4>&) { return M; })) {
    const MetricGraph g2 = rebuilt(x2, M);
    CHECK(g.adj == g2.adj);
  }
}

TEST_CASE("carried metric graph: a move that would invert a triangle is refused, the graph unchanged") {
  const Mat2 M = rotated_metric(0.2, 0.02, 0.5);
  const std::vector<Vec2> x0 = square_points(7);
  MetricGraph g = rebuilt(x0, M);
  const MetricGraph before = g;
  std::vector<Vec2> x1 = x0;
  std::swap(x1[10], x1[200]);  // two far sites trade places: their triangles turn over
  CHECK_FALSE(metric_delaunay_update(x1, g, [&](const std::array<Vec2, 4>&) { return M; }));
  CHECK(g.tris == before.tris);
  CHECK(g.adj == before.adj);
  CHECK(g.ptr == before.ptr);
  // allowed a few inverted triangles, it carries them (and counts them)
  CHECK(metric_delaunay_update(x1, g, [&](const std::array<Vec2, 4>&) { return M; }, 100));
  CHECK(g.inverted > 0);
  CHECK(g.inverted <= 100);
}

TEST_CASE("metric cells: any start guess gives the same start sites") {
  const Background bg = graded_metric_background();
  int nfixed = 0;
  const std::vector<Vec2> x = boundary_and_random(bg, 800, 3, nfixed);
  const RestrictedVoronoi exact(bg, x);  // starts from the Euclidean Delaunay graph's nearest sites
  MetricGraph mg = build_metric_graph(bg, x, DelaunayGraph(x, true, false));
  const RestrictedVoronoi guessed(bg, x, mg, std::vector<int>(bg.num_cells(), nfixed + 17));
  CHECK(guessed.starts() == exact.starts());
}

TEST_CASE("energy with the carried metric graph: the rebuilt graph's energy and gradient, to rounding") {
  const Background bg = graded_metric_background();
  int nfixed = 0;
  std::vector<Vec2> x = boundary_and_random(bg, 1500, 21, nfixed);
  EnergySettings carry, rebuild;
  rebuild.carry_metric_graph = false;
  EnergyWorkspace wc(carry), wr(rebuild);
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> U(-1, 1);
  double worst_e = 0, worst_g = 0;
  for (int step = 0; step < 4; ++step) {
    const EnergyResult a = lp_energy(bg, x, 6, true, &wc, 1.0);
    const EnergyResult b = lp_energy(bg, x, 6, true, &wr, 1.0);
    worst_e = quadapt_test::worst_of(worst_e, std::abs(a.energy - b.energy) / b.energy);
    double gmax = 0, dg = 0;
    for (size_t i = 0; i < x.size(); ++i) {
      gmax = std::max(gmax, b.grad[i].norm());
      dg = quadapt_test::worst_of(dg, (a.grad[i] - b.grad[i]).norm());
    }
    worst_g = quadapt_test::worst_of(worst_g, dg / gmax);
    CHECK(a.pieces == b.pieces);
    // small moves of the free sites (0.3 % of the mean spacing, 0.065: random points make slivers)
    for (size_t i = nfixed; i < x.size(); ++i) x[i] += 2e-4 * Vec2(U(rng), U(rng));
  }
  CHECK(wc.timers.carried >= 2);  // the graph was carried (and not only rebuilt)
  CHECK(wc.timers.tree_refits >= 1);  // ... and the site tree refitted (SiteTree::refit)
  CHECK(wr.timers.carried == 0);
  CHECK(worst_e < 1e-12);
  CHECK(worst_g < 1e-9);
}

TEST_CASE("energy with a carried graph that has inverted triangles: still the exact energy") {
  // two far sites trade places: the carried graph keeps triangles turned over (wrong and
  // missing neighbours near them); every site within the security radius still clips the
  // pieces, so energy and gradient are those of the rebuilt graph, to rounding
  const Background bg = graded_metric_background();
  int nfixed = 0;
  std::vector<Vec2> x = boundary_and_random(bg, 1500, 21, nfixed);
  EnergySettings carry, rebuild;
  carry.carry_inverted = 1;  // carry whatever inverts
  rebuild.carry_metric_graph = false;
  EnergyWorkspace wc(carry), wr(rebuild);
  lp_energy(bg, x, 6, true, &wc, 1.0);  // graph built
  lp_energy(bg, x, 6, true, &wc, 1.0);  // carried; the site tree built
  std::swap(x[nfixed + 10], x[nfixed + 900]);
  const EnergyResult a = lp_energy(bg, x, 6, true, &wc, 1.0);
  const EnergyResult b = lp_energy(bg, x, 6, true, &wr, 1.0);
  CHECK(wc.timers.carried == 2);
  CHECK(wc.timers.tree_refits == 1);  // that tree refitted to the swapped sites: still exact
  CHECK(a.pieces == b.pieces);
  CHECK(std::abs(a.energy - b.energy) < 1e-12 * b.energy);
  double gmax = 0, dg = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    gmax = std::max(gmax, b.grad[i].norm());
    dg = quadapt_test::worst_of(dg, (a.grad[i] - b.grad[i]).norm());
  }
  CHECK(dg < 1e-9 * gmax);
}

namespace {

/// A metric whose axes turn with position (5:1, 1.5 turns across the square); it counts its calls
/// (the serial loop's tests). Its answers do not depend on that state, so the graph with the
/// parallel first tests must be the serial loop's exactly.
struct TurningMetric {
  int calls = 0;
  Mat2 operator()(const std::array<Vec2, 4>& q) {
    ++calls;
    const Vec2 c = 0.25 * (q[0] + q[1] + q[2] + q[3]);
    return rotated_metric(0.05, 0.01, 3 * M_PI * (c.x() + 0.5 * c.y()));
  }
};

std::vector<Vec2> many_points(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(0, 1);
  std::vector<Vec2> x = {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)};
  for (int i = 0; i < n; ++i) x.emplace_back(U(rng), U(rng));
  return x;
}

}  // namespace

TEST_CASE("metric graph: the parallel first tests give the serial loop's graph, for any thread count") {
  // 60,000 sites: ~120,000 triangles, 30 blocks of first tests (the parallel pass needs > 4) and
  // the neighbour lists counted and filled in parallel (from 100,000 triangles)
  const std::vector<Vec2> x0 = many_points(60000, 11);
  const DelaunayGraph dt(x0, true, false);
  TurningMetric serial_m;
  const MetricGraph ref = metric_delaunay(x0, dt.triangles(), [&](const std::array<Vec2, 4>& q) { return serial_m(q); });
  REQUIRE(ref.flips > 1000);  // the turning metric flips a good part of the Euclidean edges
  const EdgeMetricFactory factory = [] { return EdgeMetric(TurningMetric{}); };
  const RestoreThreads restore;
  for (int nt : {1, 2}) {
    omp_set_num_threads(nt);
    TurningMetric m;
    const MetricGraph g =
        metric_delaunay(x0, dt.triangles(), [&](const std::array<Vec2, 4>& q) { return m(q); }, factory);
    CHECK(g.flips == ref.flips);
    CHECK(g.tris == ref.tris);
    CHECK(g.adj == ref.adj);
    CHECK(m.calls < serial_m.calls);  // the serial loop reused some of the parallel answers
    // carried to moved sites: again the serial loop's graph
    std::vector<Vec2> x1 = x0;
    for (size_t i = 4; i < x1.size(); ++i) x1[i] += 2e-4 * Vec2(std::sin(37.0 * i), std::cos(53.0 * i));
    MetricGraph a = ref, b = g;
    TurningMetric ma, mb;
    const bool oka = metric_delaunay_update(x1, a, [&](const std::array<Vec2, 4>& q) { return ma(q); }, 1000);
    const bool okb = metric_delaunay_update(x1, b, [&](const std::array<Vec2, 4>& q) { return mb(q); }, 1000, factory);
    REQUIRE(oka == okb);
    CHECK(a.flips == b.flips);
    CHECK(a.tris == b.tris);
    CHECK(a.adj == b.adj);
    CHECK(mb.calls < ma.calls / 4);  // few flips after a small move: the serial loop tests little
  }
}

namespace {

/// The graph's edges as pairs of original site numbers (perm[k]: the original number of site k).
std::vector<std::pair<int, int>> edges_of(const MetricGraph& g, const std::vector<int>& perm) {
  std::vector<std::pair<int, int>> e;
  for (int i = 0; i < g.num_sites(); ++i)
    for (const int* j = g.nbr_begin(i); j != g.nbr_end(i); ++j)
      if (i < *j) e.emplace_back(std::min(perm[i], perm[*j]), std::max(perm[i], perm[*j]));
  std::sort(e.begin(), e.end());
  return e;
}

}  // namespace

TEST_CASE("metric graph: the same graph whatever the sites' numbering, and mirrored with the problem") {
  // Where the metric varies, Lawson's flips are not confluent: the graph depends on the order of
  // the flips. Flipping the most violated edge first (metric_graph.hpp, "Flip order") makes it
  // depend on the geometry only. Before, the flips went in the triangles' order (a stack seeded
  // from triangle 0), and renumbering the sites — or mirroring the problem, which renumbers the
  // canonical frame's cells and lpcvt's sites — gave another graph here: 2,000 random sites, the
  // turning metric, which flips about a third of the Euclidean edges.
  const std::vector<Vec2> x0 = many_points(2000, 5);
  const int n = static_cast<int>(x0.size());
  TurningMetric m;
  auto build = [&](const std::vector<Vec2>& x) {
    const DelaunayGraph dt(x, true, false);
    return metric_delaunay(x, dt.triangles(), [&](const std::array<Vec2, 4>& q) { return m(q); });
  };
  std::vector<int> id(n);
  for (int i = 0; i < n; ++i) id[i] = i;
  const MetricGraph ref = build(x0);
  REQUIRE(ref.flips > 300);
  const auto ref_edges = edges_of(ref, id);
  // renumbered: the sites in a random order (the Euclidean triangulation is unique: random points)
  std::vector<int> perm = id;
  std::shuffle(perm.begin(), perm.end(), std::mt19937(3));
  std::vector<Vec2> xp(n);
  for (int k = 0; k < n; ++k) xp[k] = x0[perm[k]];
  const MetricGraph gp = build(xp);
  CHECK(gp.flips == ref.flips);
  CHECK(edges_of(gp, perm) == ref_edges);
  // mirrored: x -> -x (exact; 1 - x would round), the metric mirrored with it (M' = M Q^T,
  // Q = diag(-1, 1)), the sites in reversed order
  std::vector<Vec2> xm(n);
  std::vector<int> rev(n);
  for (int k = 0; k < n; ++k) {
    rev[k] = n - 1 - k;
    xm[k] = Vec2(-x0[rev[k]].x(), x0[rev[k]].y());
  }
  const Mat2 Q = (Mat2() << -1, 0, 0, 1).finished();
  const DelaunayGraph dtm(xm, true, false);
  const MetricGraph gm = metric_delaunay(xm, dtm.triangles(), [&](const std::array<Vec2, 4>& q) {
    std::array<Vec2, 4> back;
    for (int k = 0; k < 4; ++k) back[k] = Q * q[k];
    return Mat2(m(back) * Q.transpose());
  });
  CHECK(gm.flips == ref.flips);
  CHECK(edges_of(gm, rev) == ref_edges);
}
