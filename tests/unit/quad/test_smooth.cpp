#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include <Eigen/LU>

#include "quad/mesh_utils.hpp"
#include "quad/quality_summary.hpp"
#include "core/error.hpp"
#include "frame/frame.hpp"
#include "quad/frame_smooth.hpp"
#include "quad/smooth.hpp"
#include "quad/subdivide.hpp"
#include "mesh/jitter.hpp"

#include <omp.h>
#include "test_meshes.hpp"
#include "../worst.hpp"

using namespace quadapt;

namespace {
double cross_z(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

double angle_deviation(const Mesh& m) {  // mean |angle - 90| over quad corners
  double s = 0;
  int n = 0;
  for (int c = 0; c < m.num_cells(); ++c)
    for (int k = 0; k < m.cells[c].nv; ++k, ++n) s += std::abs(corner_angle_deg(m, c, k) - 90);
  return s / n;
}
}  // namespace

TEST_CASE("smooth: a perturbed grid improves, min angle never drops, boundary fixed") {
  for (unsigned seed : {1u, 2u, 3u, 4u, 5u}) {
    Mesh m = make_perturbed_quads(12, 9, 0.35, seed);
    Mesh before = m;
    const auto q0 = quality_summary(m);
    SmoothOptions opt;
    opt.sweeps = 5;
    auto st = angle_smooth(m, opt);
    const auto q1 = quality_summary(m);
    CHECK(st.min_angle_before == doctest::Approx(q0.min_angle_deg));
    CHECK(q1.min_angle_deg >= q0.min_angle_deg);
    CHECK(q1.min_scaled_jacobian >= std::min(q0.min_scaled_jacobian, 0.5));
    CHECK(q1.inverted == 0);
    CHECK(angle_deviation(m) < angle_deviation(before));
    CHECK(st.moves_full + st.moves_reduced > 0);
    auto fixed = boundary_node_flags(before);
    for (int v = 0; v < m.num_nodes(); ++v)
      if (fixed[v]) CHECK(m.nodes[v] == before.nodes[v]);
    CHECK(total_area(m) == doctest::Approx(1.0).epsilon(1e-12));
  }
}

TEST_CASE("smooth: an anisotropic rectangular grid is a fixed point") {
  Mesh m = make_structured_quads(5, 40, 0, 1, 0, 0.5);  // 0.2 x 0.0125 rectangles, 16:1
  Mesh before = m;
  auto st = angle_smooth(m, {});
  for (int v = 0; v < m.num_nodes(); ++v) CHECK((m.nodes[v] - before.nodes[v]).norm() < 1e-12);
  CHECK(st.min_angle_after == doctest::Approx(90));
}

TEST_CASE("smooth: the split of a random Delaunay triangulation (mixed angles) never gets worse") {
  Mesh tri = testing::delaunay_unit_square(8, 150, 5);
  Mesh m = split_to_all_quads(tri);  // 3 quads per triangle: poor angles
  const auto q0 = quality_summary(m);
  Mesh before = m;
  SmoothOptions opt;
  for (int s = 0; s < 4; ++s) {  // one sweep at a time: monotone
    opt.sweeps = 1;
    const auto prev = quality_summary(m);
    angle_smooth(m, opt);
    CHECK(quality_summary(m).min_angle_deg >= prev.min_angle_deg);
    CHECK(quality_summary(m).min_scaled_jacobian >= std::min(prev.min_scaled_jacobian, 0.5));
    CHECK(quality_summary(m).inverted == 0);
  }
  const auto q1 = quality_summary(m);
  CHECK(q1.mean_cell_min_angle_deg > q0.mean_cell_min_angle_deg);
  CHECK(angle_deviation(m) < angle_deviation(before));
}

TEST_CASE("smooth: mixed triangle/quad mesh keeps validity") {
  Mesh m = make_perturbed_quads(8, 8, 0.3, 9);
  for (int c : {10, 20, 30}) {  // split three quads into triangles
    Cell q = m.cells[c];
    m.cells[c] = Cell{{q.v[0], q.v[1], q.v[2], -1}, 3};
    m.cells.push_back(Cell{{q.v[0], q.v[2], q.v[3], -1}, 3});
  }
  const double a0 = quality_summary(m).min_angle_deg;
  angle_smooth(m, {});
  const auto q1 = quality_summary(m);
  CHECK(q1.min_angle_deg >= a0);
  CHECK(q1.inverted == 0);
}

TEST_CASE("smooth: in a constant metric T it is the physical smoothing of the mesh mapped by T") {
  // angle_smooth(m, T) = T^-1 angle_smooth(T m): every angle, rotation and guard is measured in
  // the mapped space (fails if a rotation is not mapped back by T^-1 or the guard stays physical).
  Mat2 T;
  T << 3.0, 1.2, -0.4, 0.7;  // det > 0, stretch and shear
  for (unsigned seed : {1u, 2u, 3u}) {
    Mesh m = make_perturbed_quads(10, 8, 0.3, seed);
    Mesh mapped = m;
    for (auto& x : mapped.nodes) x = T * x;
    SmoothOptions opt;
    opt.sweeps = 3;
    const auto sm = angle_smooth(m, opt, [&](const Vec2&) { return T; });
    const auto sp = angle_smooth(mapped, opt);
    CHECK(sm.moves_full == sp.moves_full);
    CHECK(sm.moves_reduced == sp.moves_reduced);
    double worst = 0;
    for (int v = 0; v < m.num_nodes(); ++v) worst = quadapt_test::worst_of(worst, (T * m.nodes[v] - mapped.nodes[v]).norm());
    CHECK(worst < 1e-12);
  }
}

TEST_CASE("smooth: in the grid's metric a perturbed boundary-layer grid keeps its first row") {
  // Rows graded by 1.5 from the wall y = 0 (first row 0.002), 20 columns; interior nodes
  // perturbed by 15% of their local spacing. The metric at y is diag(1/dx, 1/dy(y)) of the
  // unperturbed grid. Smoothing in that metric keeps the first row near its width; physical
  // angle smoothing (stretched 25:1 cells at the wall) pulls it away.
  const int nx = 20, ny = 10;
  std::vector<double> ys{0};
  for (int j = 0; j < ny; ++j) ys.push_back(ys.back() + 0.002 * std::pow(1.5, j));
  Mesh grid = make_structured_quads(nx, ny);
  for (auto& x : grid.nodes) x.y() = ys[static_cast<int>(std::lround(x.y() * ny))];
  auto row_of = [&](double y) {
    int j = 0;
    while (j + 1 < ny && ys[j + 1] <= y) ++j;
    return j;
  };
  auto metric = [&](const Vec2& x) {
    const int j = row_of(x.y());
    Mat2 M = Mat2::Zero();
    M(0, 0) = nx;
    M(1, 1) = 1.0 / (ys[j + 1] - ys[j]);
    return M;
  };
  Mesh pert = grid;
  auto fixed = boundary_node_flags(grid);
  unsigned s = 7;
  auto rnd = [&]() { s = s * 1103515245u + 12345u; return ((s >> 8) & 0xffff) / 65535.0 - 0.5; };
  for (int v = 0; v < pert.num_nodes(); ++v) {
    if (fixed[v]) continue;
    const int j = row_of(grid.nodes[v].y());
    const double dy = std::min(ys[j + 1] - ys[j], ys[j] - ys[std::max(j - 1, 0)]);
    pert.nodes[v] += Vec2(0.3 * rnd() / nx, 0.3 * rnd() * dy);
  }
  auto first_row_error = [&](const Mesh& m) {  // mean |y - 0.002| / 0.002 over the first interior row
    double e = 0;
    int n = 0;
    for (int v = 0; v < m.num_nodes(); ++v)
      if (!fixed[v] && std::abs(grid.nodes[v].y() - ys[1]) < 1e-12) e += std::abs(m.nodes[v].y() - ys[1]) / ys[1], ++n;
    return e / n;
  };
  Mesh phys = pert, metr = pert;
  SmoothOptions opt;
  opt.sweeps = 5;
  angle_smooth(phys, opt);
  angle_smooth(metr, opt, metric);
  MESSAGE("first-row error: perturbed " << first_row_error(pert) << ", physical " << first_row_error(phys)
                                        << ", metric " << first_row_error(metr));
  CHECK(first_row_error(metr) < first_row_error(pert));
  CHECK(first_row_error(metr) < 0.5 * first_row_error(phys));
  CHECK(quality_summary(metr).inverted == 0);
}

namespace {
// Mean |corner angle - 90| (degrees) and the share of edges of length in [1/sqrt2, sqrt2], both
// measured after the linear map T (the cells' corners and edges counted per cell).
std::pair<double, double> metric_shape(const Mesh& m, const Mat2& T) {
  double dev = 0, in_band = 0;
  int corners = 0, edges = 0;
  for (const Cell& c : m.cells)
    for (int k = 0; k < c.nv; ++k) {
      const Vec2 p = T * m.nodes[c.v[k]], n = T * m.nodes[c.v[(k + 1) % c.nv]], q = T * m.nodes[c.v[(k + c.nv - 1) % c.nv]];
      const Vec2 a = n - p, b = q - p;
      dev += std::abs(std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b)) * 180 / M_PI - 90);
      ++corners;
      in_band += a.norm() >= std::sqrt(0.5) && a.norm() <= std::sqrt(2.0);
      ++edges;
    }
  return {dev / corners, in_band / edges};
}
// The metric T that maps each 1/8 x 1/12 cell of the unit square to a unit square turned by 30
// degrees, that 8 x 12 grid (the shape fit's exact minimiser in T) and its fixed nodes.
struct TurnedGrid {
  Mat2 T;
  Mesh grid = make_structured_quads(8, 12);
  std::vector<char> fixed = boundary_node_flags(grid);
  TurnedGrid() {
    const double a = M_PI / 6;
    Mat2 R;
    R << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
    T = R * Eigen::Vector2d(8, 12).asDiagonal();
  }
};
/// A fixed linear congruential sequence in [-0.5, 0.5] (the same numbers on every platform).
struct Lcg {
  unsigned s;
  double operator()() { s = s * 1103515245u + 12345u; return ((s >> 8) & 0xffff) / 65535.0 - 0.5; }
};
/// The grid's interior nodes moved by up to 30 % of a cell (seed 11).
Mesh perturbed_interior(const TurnedGrid& g) {
  Lcg rnd{11};
  Mesh pert = g.grid;
  for (int v = 0; v < pert.num_nodes(); ++v)
    if (!g.fixed[v]) pert.nodes[v] += Vec2(0.6 * rnd() / 8, 0.6 * rnd() / 12);
  return pert;
}
}  // namespace

TEST_CASE("shape_smooth: a perturbed grid of the metric's unit squares is restored") {
  // T maps each 1/8 x 1/12 cell to a unit square turned by 30 degrees: the grid is the exact
  // minimiser (every corner a unit square of the metric). Interior nodes perturbed by up to 30 %
  // of a cell; the fit restores the grid (angle_smooth, which only balances angles, does not:
  // its fixed points include every grid of parallel lines, the lengths are free).
  const TurnedGrid g;
  const Mat2& T = g.T;
  const Mesh& grid = g.grid;
  const Mesh pert = perturbed_interior(g);
  Mesh m = pert, ang = pert;
  ShapeSmoothOptions opt;
  opt.sweeps = 2000;
  opt.tolerance = 1e-12;
  const auto st = shape_smooth(m, opt, [&](const Vec2&) { return T; });
  double worst = 0;
  for (int v = 0; v < m.num_nodes(); ++v) worst = quadapt_test::worst_of(worst, (T * (m.nodes[v] - grid.nodes[v])).norm());
  MESSAGE("sweeps " << st.sweeps << ", worst metric distance to the grid " << worst);
  CHECK(worst < 1e-6);
  CHECK(quality_summary(m).inverted == 0);
  SmoothOptions aopt;
  aopt.sweeps = 100;
  angle_smooth(ang, aopt, [&](const Vec2&) { return T; });
  const auto [dev_pert, band_pert] = metric_shape(pert, T);
  const auto [dev_shape, band_shape] = metric_shape(m, T);
  const auto [dev_angle, band_angle] = metric_shape(ang, T);
  MESSAGE("mean metric angle deviation: perturbed " << dev_pert << ", angle " << dev_angle << ", shape " << dev_shape);
  CHECK(dev_shape < 1e-4);
  CHECK(band_shape == 1.0);
  CHECK(dev_shape < 0.01 * dev_angle);
}

TEST_CASE("shape_smooth: over-relaxation reaches the grid in fewer sweeps") {
  // The perturbed grid above (the fit's exact minimiser is the grid). Gauss-Seidel with the
  // plain step (relaxation 1) against the default over-relaxation: the sweeps to the tolerance
  // and the distance to the grid after 30 sweeps (the default cap). Fails when the relaxation
  // is not applied (both runs the same).
  const TurnedGrid g;
  const Mat2& T = g.T;
  const Mesh& grid = g.grid;
  const Mesh pert = perturbed_interior(g);
  auto run = [&](double relaxation, int sweeps, double tolerance, int& used) {
    Mesh m = pert;
    ShapeSmoothOptions opt;
    opt.relaxation = relaxation;
    opt.sweeps = sweeps;
    opt.tolerance = tolerance;
    used = shape_smooth(m, opt, [&](const Vec2&) { return T; }).sweeps;
    CHECK(quality_summary(m).inverted == 0);
    double worst = 0;
    for (int v = 0; v < m.num_nodes(); ++v) worst = quadapt_test::worst_of(worst, (T * (m.nodes[v] - grid.nodes[v])).norm());
    return worst;
  };
  CHECK(ShapeSmoothOptions{}.relaxation == 1.6);
  int plain_used = 0, sor_used = 0, dummy = 0;
  const double plain_conv = run(1.0, 2000, 1e-8, plain_used), sor_conv = run(1.6, 2000, 1e-8, sor_used);
  const double plain30 = run(1.0, 30, 0, dummy), sor30 = run(1.6, 30, 0, dummy);
  MESSAGE("sweeps to 1e-8: plain " << plain_used << ", over-relaxed " << sor_used << "; metric distance to the grid "
                                   << "after 30 sweeps: plain " << plain30 << ", over-relaxed " << sor30);
  CHECK(plain_conv < 1e-5);
  CHECK(sor_conv < 1e-5);
  CHECK(sor_used < 0.85 * plain_used);  // measured 431 against 565
  CHECK(sor30 < 0.6 * plain30);         // measured 0.0107 against 0.0226
}

TEST_CASE("shape_smooth: in a constant metric T it is the smoothing of the mesh mapped by T") {
  // shape_smooth(m, T) = T^-1 shape_smooth(T m): the fit is made in the mapped space and mapped
  // back by T^-1 (fails if a prediction is not mapped back or the size is measured physically).
  Mat2 T;
  T << 3.0, 1.2, -0.4, 0.7;
  for (unsigned seed : {1u, 2u}) {
    Mesh m = make_perturbed_quads(10, 8, 0.3, seed);
    Mesh mapped = m;
    for (auto& x : mapped.nodes) x = T * x;
    ShapeSmoothOptions opt;
    opt.sweeps = 5;
    opt.target_edge = 0.4;
    // the parts measured in physical space are not mapped (they see m, not T m): the physical
    // guard and the revisit tolerance (a step against the node's physical edge lengths); both
    // off here, so that every node (the wall nodes slide along the mapped walls too) takes the
    // same steps
    opt.min_sine_physical = -1;
    opt.tolerance = 0;
    const auto sm = shape_smooth(m, opt, [&](const Vec2&) { return T; });
    const auto sp = shape_smooth(mapped, opt);
    CHECK(sm.moves_full == sp.moves_full);
    CHECK(sm.moves_full > 0);
    double worst = 0;
    for (int v = 0; v < m.num_nodes(); ++v) worst = quadapt_test::worst_of(worst, (T * m.nodes[v] - mapped.nodes[v]).norm());
    CHECK(worst < 1e-11);
  }
}

TEST_CASE("shape_smooth: the split of a random Delaunay triangulation stays valid and gets squarer") {
  Mesh tri = testing::delaunay_unit_square(8, 150, 5);
  const Mesh before = split_to_all_quads(tri);
  const auto fixed = boundary_node_flags(before);
  for (const bool slide : {false, true}) {
    CAPTURE(slide);
    Mesh m = before;
    ShapeSmoothOptions opt;
    opt.target_edge = std::sqrt(total_area(m) / m.num_cells());
    opt.slide_walls = slide;
    const auto st = shape_smooth(m, opt);
    CHECK(quality_summary(m).inverted == 0);
    CHECK(st.moves_full + st.moves_reduced > 0);
    CHECK(angle_deviation(m) < angle_deviation(before));
    // fixed walls: every boundary node stays; sliding: the 4 corners stay, the others (4 x 15:
    // 8 segments per side, split in two) stay on their side of the square, bit for bit
    CHECK(st.sliding_nodes == (slide ? 60 : 0));
    int moved = 0;
    for (int v = 0; v < m.num_nodes(); ++v) {
      if (!fixed[v]) continue;
      const Vec2 &a = before.nodes[v], &b = m.nodes[v];
      if (!slide || ((a.x() == 0 || a.x() == 1) && (a.y() == 0 || a.y() == 1))) {
        CHECK(b == a);
        continue;
      }
      moved += b != a;
      if (a.x() == 0 || a.x() == 1) CHECK(b.x() == a.x());
      if (a.y() == 0 || a.y() == 1) CHECK(b.y() == a.y());
    }
    if (slide) CHECK(moved > 30);
    CHECK(total_area(m) == doctest::Approx(total_area(before)).epsilon(1e-12));
  }
}

TEST_CASE("shape_smooth: on oblique walls the sliding nodes stay on their wall lines, and the fit turns with the square") {
  // the square of the test above turned by 27 degrees and moved: every sliding node must stay on
  // its wall's line x_a + t (x_b - x_a) (only axis-parallel walls were checked before, where a
  // slide that moved one coordinate alone would pass: a test audit, session 38), and the fit is
  // the turned fit of the unturned square
  Mesh tri = testing::delaunay_unit_square(8, 150, 5);
  const Mesh square = split_to_all_quads(tri);
  const double th = 27 * M_PI / 180;
  Mat2 R;
  R << std::cos(th), -std::sin(th), std::sin(th), std::cos(th);
  const Vec2 shift(0.3, -1.7);
  Mesh before = square;
  for (Vec2& p : before.nodes) p = R * p + shift;
  const auto fixed = boundary_node_flags(before);
  ShapeSmoothOptions opt;
  opt.target_edge = std::sqrt(total_area(square) / square.num_cells());
  opt.slide_walls = true;
  Mesh ref = square, m = before;
  const auto st_ref = shape_smooth(ref, opt);
  const auto st = shape_smooth(m, opt);
  CHECK(st.sliding_nodes == 60);
  CHECK(st.sliding_nodes == st_ref.sliding_nodes);
  CHECK(quality_summary(m).inverted == 0);
  int moved = 0;
  double off_wall = 0, off_turned = 0;
  for (int v = 0; v < m.num_nodes(); ++v) {
    off_turned = quadapt_test::worst_of(off_turned, (m.nodes[v] - (R * ref.nodes[v] + shift)).norm());
    if (!fixed[v]) continue;
    const Vec2 a = square.nodes[v], b = R.transpose() * (m.nodes[v] - shift);  // b in the square's frame
    moved += (m.nodes[v] - before.nodes[v]).norm() > 1e-9;
    if (a.x() == 0 || a.x() == 1) off_wall = quadapt_test::worst_of(off_wall, std::abs(b.x() - a.x()));
    if (a.y() == 0 || a.y() == 1) off_wall = quadapt_test::worst_of(off_wall, std::abs(b.y() - a.y()));
  }
  CHECK(moved > 30);
  CHECK(off_wall < 1e-12);
  CHECK(off_turned < 1e-9);
  CHECK(total_area(m) == doctest::Approx(total_area(before)).epsilon(1e-12));
}

TEST_CASE("wall_slides: straight-wall nodes, not corners, group ends, hanging nodes or curved walls") {
  // 4 x 3 grid: 3 + 2 + 3 + 2 wall nodes between the corners
  Mesh m = make_structured_quads(4, 3);
  auto nodes = [](const Mesh& mesh) {
    std::vector<int> v;
    for (const WallSlide& w : wall_slides(mesh)) v.push_back(w.node);
    return v;
  };
  CHECK(nodes(m).size() == 10);
  for (const WallSlide& w : wall_slides(m)) {  // a, b: the node's wall neighbours, on its line
    CHECK((m.nodes[w.a] - m.nodes[w.node]).norm() == doctest::Approx((m.nodes[w.b] - m.nodes[w.node]).norm()));
    CHECK(std::abs(cross_z(m.nodes[w.a] - m.nodes[w.node], m.nodes[w.b] - m.nodes[w.node])) < 1e-15);
  }
  // the bottom wall's middle node (2, 0) becomes the end of a group: it stays
  Mesh g = m;
  g.groups.push_back({6, "inflow"});
  g.boundary[2].group = g.boundary[3].group = 4;  // edges (2,0)-(3,0), (3,0)-(4,0)
  CHECK(nodes(g).size() == 9);
  for (int v : nodes(g)) CHECK(v != 2);
  // a wall node off its neighbours' line (a polyline of a curved wall): it stays, and so does
  // its neighbour 2 (now off the line of 1 and 3)
  Mesh c = m;
  c.nodes[1].y() = -1e-6;
  CHECK(nodes(c).size() == 8);
  for (int v : nodes(c)) CHECK((v != 1 && v != 2));
  // no boundary listed: the free edges alone
  Mesh f = m;
  f.boundary.clear();
  CHECK(nodes(f) == nodes(m));
  // a hanging node: (1, 0.5) halves the big cell's edge (1,0)-(1,1)
  Mesh h;
  h.nodes = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {2, 0}, {2, 0.5}, {2, 1}, {1, 0.5}};
  Cell q;
  q.nv = 4;
  q.v = {0, 1, 2, 3};
  h.cells.push_back(q);
  q.v = {1, 4, 5, 7};
  h.cells.push_back(q);
  q.v = {7, 5, 6, 2};
  h.cells.push_back(q);
  const auto hv = nodes(h);
  CHECK(std::find(hv.begin(), hv.end(), 7) == hv.end());
  CHECK(std::find(hv.begin(), hv.end(), 5) != hv.end());  // the right wall's middle node slides
}

TEST_CASE("shape_smooth: wall nodes displaced along their walls slide back to the metric's grid") {
  // The grid of the metric's unit squares (as above, turned by 30 degrees in the metric), its
  // interior nodes perturbed and its wall nodes moved along their walls by up to 30 % of a cell.
  // With sliding walls the fit restores the grid; with fixed walls it cannot (the rows must end
  // where the wall nodes are).
  const TurnedGrid g;
  const Mat2& T = g.T;
  const Mesh& grid = g.grid;
  const auto& fixed = g.fixed;
  Lcg rnd{7};
  Mesh pert = grid;
  for (int v = 0; v < pert.num_nodes(); ++v) {
    Vec2& x = pert.nodes[v];
    const bool wx = x.x() == 0 || x.x() == 1, wy = x.y() == 0 || x.y() == 1;
    if (!fixed[v]) x += Vec2(0.6 * rnd() / 8, 0.6 * rnd() / 12);
    else if (wx && !wy) x.y() += 0.6 * rnd() / 12;  // left / right wall
    else if (wy && !wx) x.x() += 0.6 * rnd() / 8;   // bottom / top wall
  }
  double worst_by[2];
  for (const bool slide : {false, true}) {
    Mesh m = pert;
    ShapeSmoothOptions opt;
    opt.sweeps = 4000;
    opt.tolerance = 1e-12;
    opt.slide_walls = slide;
    const auto st = shape_smooth(m, opt, [&](const Vec2&) { return T; });
    double worst = 0;
    for (int v = 0; v < m.num_nodes(); ++v) worst = quadapt_test::worst_of(worst, (T * (m.nodes[v] - grid.nodes[v])).norm());
    MESSAGE("slide " << slide << ": sweeps " << st.sweeps << ", wall nodes sliding " << st.sliding_nodes
                     << ", worst metric distance to the grid " << worst);
    CHECK(quality_summary(m).inverted == 0);
    for (int v = 0; v < m.num_nodes(); ++v) {  // walls: on their side of the square, bit for bit
      const Vec2 &g = grid.nodes[v], &x = m.nodes[v];
      if (g.x() == 0 || g.x() == 1) CHECK(x.x() == g.x());
      if (g.y() == 0 || g.y() == 1) CHECK(x.y() == g.y());
    }
    worst_by[slide] = worst;
  }
  CHECK(worst_by[1] < 1e-6);
  CHECK(worst_by[0] > 0.05);
}

TEST_CASE("shape_smooth: one node's step minimises the corner fit with every corner in its own node's (or its cell's) metric") {
  // 2 x 2 quads, one interior node (perturbed), a metric that varies in space. The documented
  // step: every corner the node takes part in is fitted (z clamped) in the metric at the
  // corner's own node, and the node goes to the minimiser of the sum of the squared residuals.
  // Recomputed here independently; fitting every corner in the moving node's metric (an energy
  // that changes with the node moved) gives a different point and fails. With cell_metric every
  // corner is fitted in the metric at its cell's centroid instead (--corner-metric cell).
  Vec2 expected_by[2];
  for (const bool cell_metric : {false, true}) {
    CAPTURE(cell_metric);
    Mesh m = make_structured_quads(2, 2);
    int centre = -1;
    const auto fixed = boundary_node_flags(m);
    for (int v = 0; v < m.num_nodes(); ++v)
      if (!fixed[v]) centre = v;
    REQUIRE(centre >= 0);
    m.nodes[centre] += Vec2(0.07, -0.05);
    auto metric = [](const Vec2& x) {
      Mat2 T;
      T << 2.0 + 3 * x.x(), 0.4 * x.y(), -0.3 * x.x(), 1.5 + 2 * x.y() * x.y();
      return T;
    };
    ShapeSmoothOptions opt;
    opt.sweeps = 1;
    opt.target_edge = 1.0;
    opt.size_min = 0.9;
    opt.size_max = 1.1;
    opt.cell_metric = cell_metric;
    opt.slide_walls = false;  // the interior node alone (the wall nodes' step: the test below)
    // expected: normal equations of sum |T_j (x - x_ref) - b|^2
    Mat2 A = Mat2::Zero();
    Vec2 rhs = Vec2::Zero();
    const Vec2 xi = m.nodes[centre];
    for (const Cell& c : m.cells) {
      int k = -1;
      for (int q = 0; q < 4; ++q)
        if (c.v[q] == centre) k = q;
      if (k < 0) continue;
      for (int j : {k, (k + 3) % 4, (k + 1) % 4}) {
        const Vec2 xj = m.nodes[c.v[j]], xn = m.nodes[c.v[(j + 1) % 4]], xp = m.nodes[c.v[(j + 3) % 4]];
        const Mat2 T = cell_metric ? metric(cell_centroid(m, static_cast<int>(&c - m.cells.data()))) : metric(xj);
        const Vec2 a0 = T * (xn - xj), a1 = T * (xp - xj);
        // z = (a0 + conj(i) a1) / 2, conj(i) a1 = (a1.y, -a1.x)
        Vec2 z = 0.5 * Vec2(a0.x() + a1.y(), a0.y() - a1.x());
        z *= std::clamp(z.norm(), 0.9, 1.1) / z.norm();
        const Vec2 b0 = z, b1(-z.y(), z.x());  // z, i z
        const Mat2 G = T.transpose() * T;
        auto add = [&](const Vec2& ref, const Vec2& b) {
          A += G;
          rhs += G * ref + T.transpose() * b;
        };
        if (j == k) {
          add(xn, -b0);
          add(xp, -b1);
        } else if (j == (k + 3) % 4) {
          add(xj, b0);
        } else {
          add(xj, b1);
        }
      }
    }
    const Vec2 expected = A.inverse() * rhs;
    const auto st = shape_smooth(m, opt, metric);
    REQUIRE(st.moves_full == 1);
    // the step to the minimiser, over-relaxed (ShapeSmoothOptions::relaxation)
    const Vec2 relaxed = xi + opt.relaxation * (expected - xi);
    MESSAGE("moved " << (m.nodes[centre] - xi).norm() << ", off the over-relaxed step by " << (m.nodes[centre] - relaxed).norm());
    CHECK((m.nodes[centre] - relaxed).norm() < 1e-12);
    CHECK((expected - xi).norm() > 1e-3);
    expected_by[cell_metric] = expected;
  }
  CHECK((expected_by[0] - expected_by[1]).norm() > 1e-3);  // the two metrics give different steps
}

TEST_CASE("shape_smooth: colours of >= 2048 nodes move in parallel, the same mesh at 1 and 2 threads") {
  // 120 x 120 grid, interior nodes jittered: 14,161 interior nodes in 4 colours of ~3,540 (each
  // above the parallel threshold); a graded, rotated metric so that the fit moves every node.
  Mesh start = make_structured_quads(120, 120);
  jitter_interior_nodes(start, {0.3, 5});
  const NodeMetric metric = [](const Vec2& x) {
    const double a = 0.5 + x.x();
    Mat2 R;
    R << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
    return Mat2(R * Eigen::Vector2d(120 * (1 + x.y()), 40).asDiagonal());
  };
  ShapeSmoothOptions opt;
  opt.sweeps = 5;
  const int threads = omp_get_max_threads();
  Mesh one = start, two = start;
  omp_set_num_threads(1);
  const SmoothStats s1 = shape_smooth(one, opt, metric);
  omp_set_num_threads(2);
  const SmoothStats s2 = shape_smooth(two, opt, metric);
  omp_set_num_threads(threads);
  CHECK(s1.moves_full > 10000);
  CHECK(s1.moves_full == s2.moves_full);
  CHECK(s1.moves_reduced == s2.moves_reduced);
  CHECK(s1.moves_rejected == s2.moves_rejected);
  CHECK(s1.max_displacement == s2.max_displacement);
  int differ = 0;
  for (int v = 0; v < start.num_nodes(); ++v) differ += one.nodes[v] != two.nodes[v];
  CHECK(differ == 0);
  CHECK(quality_summary(two).inverted == 0);
}

TEST_CASE("shape_smooth_to_frame: quadsmooth --frame's fit; an empty frame is an InputError") {
  // a constant frame of half-axes h: its target edge 2h in physical space. A jittered grid of
  // squares of side 2h is pulled back to squares (the mean corner angle deviation falls)
  const int n = 6;
  const double h = 0.5 / n;
  Frame f;
  f.mesh = make_structured_quads(2, 2);
  f.M.assign(4, Mat2::Identity() / h);
  Mesh m = make_perturbed_quads(n, n, 0.25, 3);
  const double before = quality_summary(m).min_angle_deg;
  const SmoothStats st = shape_smooth_to_frame(m, f);
  CHECK(st.sweeps > 0);
  CHECK(quality_summary(m).min_angle_deg > before + 5);
  Mesh untouched = make_perturbed_quads(n, n, 0.25, 3);
  CHECK_THROWS_AS(shape_smooth_to_frame(untouched, Frame{}), InputError);
}

TEST_CASE("shape_smooth: options outside their documented ranges are an InputError") {
  Mesh m = make_perturbed_quads(3, 3, 0.2, 1);
  ShapeSmoothOptions o;
  o.relaxation = 5;
  CHECK_THROWS_AS(shape_smooth(m, o), InputError);
  o = ShapeSmoothOptions{};
  o.sweeps = -1;
  CHECK_THROWS_AS(shape_smooth(m, o), InputError);
  CHECK(m.nodes == make_perturbed_quads(3, 3, 0.2, 1).nodes);  // nothing moved
}

namespace {

/// m with its nodes renumbered: node v of the result is node perm[v] of m (perm a permutation
/// of 0..n-1, checked); cells and boundary edges follow.
Mesh renumbered(const Mesh& m, const std::vector<int>& perm) {
  const int nn = m.num_nodes();
  REQUIRE(std::set<int>(perm.begin(), perm.end()).size() == static_cast<size_t>(nn));
  std::vector<int> where(nn);
  for (int v = 0; v < nn; ++v) where[perm[v]] = v;
  Mesh r = m;
  for (int v = 0; v < nn; ++v) r.nodes[v] = m.nodes[perm[v]];
  for (Cell& c : r.cells)
    for (int k = 0; k < c.nv; ++k) c.v[k] = where[c.v[k]];
  for (BoundaryEdge& e : r.boundary)
    for (int& v : e.v) v = where[v];
  return r;
}

}  // namespace

TEST_CASE("shape_smooth: the same mesh whatever the nodes' numbering, and turned with the problem") {
  // The fit is Gauss-Seidel across colours, so the colouring decides the result of a fit that has
  // not converged; greedy in index order it followed the file's numbering (here: the renumbered
  // and the turned copies 0.043 apart from the original after 8 sweeps). Greedy in the order of
  // the nodes' distance from their centroid, in each node's metric, it follows the geometry: a
  // renumbered copy, and a copy turned by 90 degrees about the origin (x, y) -> (-y, x) with the
  // metric turned with it, give the same nodes. A split random Delaunay triangulation of the unit
  // square, a graded, turning metric.
  Mesh tri = testing::delaunay_unit_square(8, 150, 5);
  Mesh start = split_to_all_quads(tri);
  // the wall nodes moved along their walls so that no two are as far from the centroid (the
  // distance's ties go by x, then y, which a turn does not keep)
  for (Vec2& x : start.nodes) {
    const bool vert = x.x() == 0 || x.x() == 1, horiz = x.y() == 0 || x.y() == 1;
    if (vert && !horiz) x.y() += 0.013 * std::sin(7.9 * x.y() + 2.3 * x.x() + 1.9);
    if (horiz && !vert) x.x() += 0.01 * std::sin(12.3 * x.x() + 4.1 * x.y() + 0.7);
  }
  const NodeMetric metric = [](const Vec2& x) {
    const double a = 0.5 + 2 * x.x();
    Mat2 R;
    R << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
    return Mat2(Eigen::Vector2d(20 * (1 + 2 * x.y()), 8).asDiagonal() * R.transpose());
  };
  ShapeSmoothOptions opt;
  opt.target_edge = std::sqrt(total_area(start) / start.num_cells());
  opt.slide_walls = true;
  opt.sweeps = 8;
  Mesh ref = start;
  const SmoothStats s0 = shape_smooth(ref, opt, metric);
  REQUIRE(!s0.converged);  // stopped by the sweeps (as quadsmooth's 30 on PHiLiP's frames): the order matters there
  // renumbered: node v of the copy is node perm[v] of the start
  const int nn = start.num_nodes();
  std::vector<int> perm(nn);
  for (int v = 0; v < nn; ++v) perm[v] = (7919 * v + 13) % nn;  // 7919 prime, no factor of nn
  Mesh renum = renumbered(start, perm);
  Mesh turned = renum;  // before the fit
  shape_smooth(renum, opt, metric);
  double d = 0;
  for (int v = 0; v < nn; ++v) d = quadapt_test::worst_of(d, (renum.nodes[v] - ref.nodes[perm[v]]).norm());
  CHECK(d < 1e-12);
  // turned: x -> Q x, the metric M(Q^T x) Q^T, and the nodes renumbered too
  Mat2 Q;
  Q << 0, -1, 1, 0;
  for (Vec2& x : turned.nodes) x = Q * x;
  const NodeMetric turned_metric = [&](const Vec2& x) { return Mat2(metric(Q.transpose() * x) * Q.transpose()); };
  shape_smooth(turned, opt, turned_metric);
  double dt = 0;
  for (int v = 0; v < nn; ++v) dt = quadapt_test::worst_of(dt, (Q.transpose() * turned.nodes[v] - ref.nodes[perm[v]]).norm());
  CHECK(dt < 1e-12);
}

TEST_CASE("smooth: the same mesh whatever the nodes' numbering") {
  // The angle smoothing is Gauss-Seidel over the nodes; in index order its 3 sweeps followed the
  // file's numbering (here 0.019 apart, 0.042 in a metric). It visits them in the order of their distance from the
  // centroid (in the metric, when it has one), so a renumbered copy gives the same nodes.
  Mesh tri = testing::delaunay_unit_square(8, 150, 7);
  const Mesh start = split_to_all_quads(tri);
  const int nn = start.num_nodes();
  std::vector<int> perm(nn);
  for (int v = 0; v < nn; ++v) perm[v] = (7919 * v + 29) % nn;
  const Mesh renum = renumbered(start, perm);
  Mat2 T;
  T << 3.0, 1.2, -0.4, 0.7;
  for (const bool with_metric : {false, true}) {
    CAPTURE(with_metric);
    const NodeMetric metric = with_metric ? NodeMetric([&](const Vec2&) { return T; }) : NodeMetric();
    Mesh a = start, b = renum;
    const SmoothStats sa = angle_smooth(a, SmoothOptions{}, metric), sb = angle_smooth(b, SmoothOptions{}, metric);
    CHECK(sa.moves_full > 100);
    CHECK(sa.moves_full == sb.moves_full);
    double d = 0;
    for (int v = 0; v < nn; ++v) d = quadapt_test::worst_of(d, (b.nodes[v] - a.nodes[perm[v]]).norm());
    CHECK(d < 1e-12);
  }
}
