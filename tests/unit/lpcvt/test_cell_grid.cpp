// The security-radius search's bucket grid (lpcvt/cell_grid.hpp): every site of a covered disk
// among its candidates, uncovered disks refused, and the pieces of RestrictedVoronoi the same
// bit for bit whether the grid or the site tree answers; the site tree's ellipse query
// (SiteTree::query_ellipse): every site of the ellipse, far fewer than its box, the same pieces.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "helpers.hpp"
#include "lpcvt/cell_grid.hpp"
#include "lpcvt/metric_graph.hpp"
#include "lpcvt/rvd.hpp"
#include "lpcvt/site_tree.hpp"

using namespace lpcvt_test;

namespace {
/// n sites uniform in the unit square, drawn from rng.
std::vector<Vec2> uniform_sites(std::mt19937& rng, int n) {
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Vec2> x(n);
  for (auto& p : x) p = Vec2(u(rng), u(rng));
  return x;
}

/// Boundary and random sites on the graded, turning frame of helpers.hpp (12 x 12 cells), their
/// metric graph and site tree: what the RestrictedVoronoi of each search are built from.
struct GradedSites {
  Background bg = graded_metric_background();
  int nfixed = 0;
  std::vector<Vec2> x;
  MetricGraph mg;
  SiteTree tree;
  GradedSites(int n, unsigned seed)
      : x(boundary_and_random(bg, n, seed, nfixed)), mg(build_metric_graph(bg, x, DelaunayGraph(x, true, false))), tree(x) {}
  RestrictedVoronoi rvd() const { return RestrictedVoronoi(bg, x, mg, std::vector<int>(bg.num_cells(), nfixed), &tree); }
};

/// The same pieces, bit for bit.
bool same_pieces(const std::vector<RvdPiece>& a, const std::vector<RvdPiece>& b) {
  if (a.size() != b.size()) return false;
  for (size_t k = 0; k < a.size(); ++k)
    if (!(a[k].site == b[k].site && a[k].cell == b[k].cell && a[k].v == b[k].v && a[k].label == b[k].label)) return false;
  return true;
}
}  // namespace

TEST_CASE("cell grid: a covered disk's sites are all candidates; a disk reaching outside is refused") {
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> u(0, 1);
  const std::vector<Vec2> x = uniform_sites(rng, 20000);
  const SiteTree tree(x);
  // a 10:1 metric at 35 degrees (the ellipses' axis-aligned boxes are far larger than them)
  const Mat2 M = rotated_metric(0.02, 0.002, 0.61);
  const Mat2 G = M.transpose() * M;
  const Vec2 q[4] = {Vec2(0.4, 0.4), Vec2(0.6, 0.42), Vec2(0.58, 0.6), Vec2(0.41, 0.57)};
  CellGrid grid;
  REQUIRE(grid.build(G, q, 4, 8.0, 1.5, tree, x, 1 << 20));
  int covered = 0, refused = 0;
  for (int k = 0; k < 400; ++k) {
    const Vec2 c(0.3 + 0.4 * u(rng), 0.3 + 0.4 * u(rng));
    const double r = 0.5 + 6 * u(rng);  // in metric units
    std::vector<int> cand;
    if (!grid.candidates(c, r, cand)) {
      CHECK(cand.empty());
      ++refused;
      continue;
    }
    ++covered;
    std::sort(cand.begin(), cand.end());
    CHECK(std::adjacent_find(cand.begin(), cand.end()) == cand.end());  // each site once
    for (int i = 0; i < static_cast<int>(x.size()); ++i) {
      const Vec2 d = x[i] - c;
      if (d.dot(G * d) < r * r && !std::binary_search(cand.begin(), cand.end(), i)) {
        FAIL_CHECK("site " << i << " in the disk but not a candidate");
        break;
      }
    }
  }
  CHECK(covered > 50);  // both answers occur
  CHECK(refused > 50);
  // a grid finer than max_buckets allows is refused
  CHECK_FALSE(grid.build(G, q, 4, 8.0, 1e-3, tree, x, 1 << 20));
  CHECK(grid.empty());
  std::vector<int> none;
  CHECK_FALSE(grid.candidates(Vec2(0.5, 0.5), 1.0, none));
}

TEST_CASE("metric pieces: the bucket grid gives the site tree's pieces, bit for bit") {
  // a graded, turning frame (helpers.hpp) on 12 x 12 cells with ~70 sites per cell: the grid
  // answers most searches (and the tree the disks that reach beyond it)
  const GradedSites g(10000, 41);
  RestrictedVoronoi with_tree = g.rvd(), with_grid = g.rvd();
  with_tree.set_grid_min_sites(0);
  with_grid.set_grid_min_sites(1);
  RvdWorkspace wt, wg;
  const std::vector<RvdPiece> a = with_tree.all_pieces(&wt), b = with_grid.all_pieces(&wg);
  CHECK(wt.grid_searches == 0);
  CHECK(wg.grid_builds > 100);
  CHECK(wg.grid_searches > wg.box_queries + wg.box_hits);  // mostly the grid
  CHECK(same_pieces(a, b));
}

TEST_CASE("metric pieces: a strongly anisotropic oblique cell takes the grid with few sites") {
  // 50:1 at 30 degrees on 8 x 8 cells, ~10 sites a cell: below the default 32 sites, but the
  // site tree's boxes hold ~30x the ellipses' sites (rvd.cpp), so the grid answers (before:
  // never, and lpcvt spent 2-2.5x the CPU on such frames). The pieces stay the tree's.
  Mesh m = quadapt::make_structured_quads(8, 8);
  set_frame(m, 0.05, 0.001, 0.5236);
  Background bg = Background::from_frame(m, 1.0, "mem");
  bg.set_metric_cells(true);
  int nfixed = 0;
  const std::vector<Vec2> x = boundary_and_random(bg, 640, 7, nfixed);
  const MetricGraph mg = build_metric_graph(bg, x, DelaunayGraph(x, true, false));
  const SiteTree tree(x);
  RestrictedVoronoi with_tree(bg, x, mg, std::vector<int>(bg.num_cells(), nfixed), &tree);
  RestrictedVoronoi by_default(bg, x, mg, std::vector<int>(bg.num_cells(), nfixed), &tree);
  with_tree.set_grid_min_sites(0);
  REQUIRE(RestrictedVoronoi::kGridMinSites == 32);
  RvdWorkspace wt, wd;
  const std::vector<RvdPiece> a = with_tree.all_pieces(&wt), b = by_default.all_pieces(&wd);
  CAPTURE(wd.grid_builds);
  CAPTURE(wd.grid_searches);
  CAPTURE(wd.box_queries);
  CHECK(wd.grid_builds > 32);  // most of the 64 cells
  CHECK(wd.grid_searches > wd.box_queries + wd.box_hits);
  CHECK(same_pieces(a, b));
}

TEST_CASE("site tree: an ellipse query lists every site of a thin oblique ellipse, far fewer than its box") {
  std::mt19937 rng(37);
  std::uniform_real_distribution<double> u(0, 1);
  const std::vector<Vec2> x = uniform_sites(rng, 20000);
  const SiteTree tree(x);
  // 500:1 at 30 degrees (the metric cells' G of a 1000:1 frame): its box holds ~280x its area
  const Mat2 M = rotated_metric(0.2, 0.0004, 0.5236);
  const Mat2 G = M.transpose() * M, Gi = G.inverse();
  long inside = 0, listed = 0, boxed = 0;
  for (int k = 0; k < 200; ++k) {
    const Vec2 c(u(rng), u(rng));
    const double r2 = std::pow(0.2 + 3 * u(rng), 2);
    std::vector<int> e, b;
    tree.query_ellipse(c, G, r2, e);
    tree.query(c - Vec2(std::sqrt(r2 * Gi(0, 0)), std::sqrt(r2 * Gi(1, 1))),
               c + Vec2(std::sqrt(r2 * Gi(0, 0)), std::sqrt(r2 * Gi(1, 1))), b);
    std::sort(e.begin(), e.end());
    CHECK(std::adjacent_find(e.begin(), e.end()) == e.end());  // each site once
    for (int i = 0; i < static_cast<int>(x.size()); ++i) {
      const Vec2 d = x[i] - c;
      if (d.dot(G * d) < r2) {
        ++inside;
        if (!std::binary_search(e.begin(), e.end(), i)) {
          FAIL_CHECK("site " << i << " in the ellipse but not listed");
          break;
        }
      }
    }
    listed += static_cast<long>(e.size());
    boxed += static_cast<long>(b.size());
  }
  REQUIRE(inside > 1000);
  CHECK(listed < 2 * inside);   // the ellipse's sites and a margin (kEllipseSlack)
  CHECK(boxed > 50 * inside);   // what the box query gave
}

TEST_CASE("metric pieces: the site tree's ellipse queries give its box queries' pieces, bit for bit") {
  const GradedSites g(3000, 43);
  RestrictedVoronoi boxes = g.rvd(), ellipses = g.rvd();
  for (RestrictedVoronoi* r : {&boxes, &ellipses}) r->set_grid_min_sites(0);  // every search asks the tree
  boxes.set_ellipse_ratio(std::numeric_limits<double>::infinity());
  ellipses.set_ellipse_ratio(0);
  RvdWorkspace wb, we;
  const std::vector<RvdPiece> a = boxes.all_pieces(&wb), b = ellipses.all_pieces(&we);
  CHECK(wb.ellipse_queries == 0);
  CHECK(we.ellipse_queries > 1000);
  CHECK(we.box_queries + we.box_hits == 0);
  CHECK(same_pieces(a, b));
}
