// split_merge / adjust_count (lpcvt/split_merge.hpp): no free site is put on a wall that is
// oblique to the axes.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "helpers.hpp"
#include "lpcvt/split_merge.hpp"

using namespace lpcvt_test;

namespace {

/// The unit square's 8 x 8 grid turned by `deg` degrees about the origin.
Mesh turned_square(double deg) {
  Mesh m = quadapt::make_structured_quads(8, 8);
  const double c = std::cos(deg * M_PI / 180), s = std::sin(deg * M_PI / 180);
  for (auto& p : m.nodes) p = Vec2(c * p.x() - s * p.y(), s * p.x() + c * p.y());
  return m;
}

/// Smallest distance from a free site (index >= nfixed) to the boundary polyline.
double closest_to_wall(const std::vector<Vec2>& s, int nfixed, const std::vector<std::array<int, 2>>& segments) {
  double best = 1e300;
  for (size_t i = nfixed; i < s.size(); ++i)
    for (const auto& g : segments) best = std::min(best, quadapt::segment_distance(s[i], s[g[0]], s[g[1]]));
  return best;
}

}  // namespace

TEST_CASE("adjust_count puts no free site on a wall oblique to the axes") {
  // The wall points of a turned square lie on their lines only up to rounding, so the Delaunay
  // graph joins some of them across a third; splitting such a chord put a free site on the wall
  // (distance ~1e-16), a sliver that no minimisation moves (the loops on rotated problems,
  // docs/studies.md). Isotropic frame: target edge 2 h = 0.06; wall points ~0.03 apart.
  for (double deg : {30.0, 15.0, 45.0}) {
    CAPTURE(deg);
    Mesh m = turned_square(deg);
    set_frame(m, 0.03, 0.03, 0.0);
    Background bg = Background::from_frame(m, 0.25, "mem");
    auto b = mesh_boundary(bg, boundary_curves(bg));
    const int nfixed = static_cast<int>(b.points.size());
    std::vector<Vec2> s = b.points;
    for (const Vec2& p : random_inside(bg, 200, 5)) {  // interior sites at least 0.05 off the walls
      std::vector<Vec2> one = b.points;
      one.push_back(p);
      if (closest_to_wall(one, nfixed, b.segments) > 0.05) s.push_back(p);
    }
    SplitMergeOptions o;
    const int target = static_cast<int>(s.size()) + 100;
    adjust_count(bg, s, nfixed, b.segments, target, o);
    CHECK(static_cast<int>(s.size()) == target);
    const double d = closest_to_wall(s, nfixed, b.segments);
    MESSAGE(deg << " degrees: " << nfixed << " wall points, closest free site " << d << " from a wall");
    CHECK(d > 1e-3);  // a midpoint between a wall point and an interior site: 0.025 off or more
    // split_merge (each cycle) measures the same edges: with every site on the wall, nothing
    // but chords; those along a wall are not split, those across the square are
    std::vector<Vec2> w = b.points;
    SplitMergeResult sm = split_merge(bg, w, nfixed, b.segments, o);
    CHECK(sm.splits > 0);
    CHECK(closest_to_wall(w, nfixed, b.segments) > 1e-3);
  }
}

TEST_CASE("adjust_count still splits chords across the domain: from the wall points alone") {
  // With no free site, every measured edge joins two wall points; the chords across the square
  // (and those cutting its corners) must still be split, or no count could be reached.
  Mesh m = turned_square(30.0);
  set_frame(m, 0.1, 0.1, 0.0);
  Background bg = Background::from_frame(m, 0.25, "mem");
  auto b = mesh_boundary(bg, boundary_curves(bg));
  const int nfixed = static_cast<int>(b.points.size());
  std::vector<Vec2> s = b.points;
  SplitMergeOptions o;
  const int change = adjust_count(bg, s, nfixed, b.segments, nfixed + 30, o);
  CHECK(change == 30);
  CHECK(closest_to_wall(s, nfixed, b.segments) > 1e-3);
}
