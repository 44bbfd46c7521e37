// estimate_frame on curved cells (docs/curved.md): the DG field's values sit at the GLL points of
// each cell's curved map, and the reconstruction integrates on that map. On the curved disk
// (tests/unit/mesh/curved_disk.hpp: 5 patches, every ring cell curved) with u = x^3 + 2 y^3
// interpolated at degree p = 2, the third directional derivative's extremes are A1 = 2 along
// phi = pi/2 and A2 = 1, exactly. The estimate from a degree-p field is not exact (the
// interpolant is not a cubic), so the test compares mean errors over the cells with two
// references: the straight-sided cells with the field interpolated on them (the estimator's
// own accuracy) and the curved field read on the straight (vertex) view of its cells (what a
// tool that ignores the map sees).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "../mesh/curved_disk.hpp"
#include "estimate/estimate_frame.hpp"
#include "estimate/interpolate.hpp"

using namespace quadapt;

namespace {
struct Errors {
  double a1 = 0, phi = 0;  // mean over cells of |A1 - 2| / 2 and of the angle error of phi
};
Errors estimate_errors(const Mesh& m) {
  const EstimateResult r = estimate_frame(m);
  Errors e;
  const int nc = m.num_cells();
  for (int c = 0; c < nc; ++c) {
    e.a1 += std::abs(r.A1[c] - 2) / 2 / nc;
    const double d = std::fmod(std::abs(r.phi[c] - M_PI / 2), M_PI);
    e.phi += std::min(d, M_PI - d) / nc;
  }
  return e;
}
}  // namespace

TEST_CASE("estimate_frame on curved cells: as accurate as on straight cells; the vertex view of the same field is not") {
  // Measured (q = 2; q = 3 within 25 %), n = 2, 4, 8: mean |A1 - 2|/2 curved 0.050, 0.040, 0.021,
  // straight cells 0.074, 0.039, 0.025, vertex view 0.34, 0.11, 0.16; phi error curved 0.040,
  // 0.016, 0.0063, straight 0.032, 0.012, 0.0056, vertex view 0.24, 0.082, 0.15.
  auto u = [](double x, double y) { return x * x * x + 2 * y * y * y; };
  for (int q : {2, 3}) {
    Errors first;
    for (int n : {2, 4, 8}) {
      CAPTURE(q);
      CAPTURE(n);
      Mesh m = curvedtest::curved_disk(n, q);
      m.set_field(interpolate_dg(m, 2, u));  // values at the GLL points of the curved map
      const Errors curved = estimate_errors(m);
      Mesh vertex_view = m;  // the same values read on the cells' straight (vertex) view
      vertex_view.curved = CurvedGeometry{};
      const Errors vertex = estimate_errors(vertex_view);
      Mesh straight = vertex_view;  // straight cells with the field interpolated on them
      straight.cell_node_fields.clear();
      straight.set_field(interpolate_dg(straight, 2, u));
      const Errors flat = estimate_errors(straight);
      CHECK(curved.a1 < 1.2 * flat.a1);
      CHECK(curved.phi < 1.6 * flat.phi);
      CHECK(vertex.a1 > 2 * curved.a1);
      CHECK(vertex.phi > 3 * curved.phi);
      if (n == 2) first = curved;
      if (n == 8) {
        CHECK(curved.a1 < 0.5 * first.a1);
        CHECK(curved.phi < 0.25 * first.phi);
      }
    }
  }
  // The SHAPE mesh of a curved solution is its vertex view (size-solve's background mesh).
  Mesh m = curvedtest::curved_disk(2, 3);
  m.set_field(interpolate_dg(m, 2, u));
  const Mesh shape = make_shape_mesh(m, estimate_frame(m));
  CHECK(shape.geometric_order() == 1);
  CHECK(shape.nodes == m.nodes);
  CHECK(shape.num_cells() == m.num_cells());
}
