#pragma once
// Flat boundary corners: a boundary vertex v that only one quad Q touches, on a smooth part of
// the boundary, gives Q an angle at v equal to the boundary's own angle there — 157.5 degrees at a
// vertex of a 16-gon, ~180 degrees on a straight wall. Such a quad is nearly a triangle (scaled
// Jacobian sin(angle)), no node move can open it (v stays on the boundary, its neighbours too),
// and on a curved domain it cannot be curved at all: once both of its boundary edges follow the
// same smooth curve their tangents at v are opposite, so the map's Jacobian vanishes at v
// (docs/curved.md; a review found the annulus loops' curving step falling back to straight
// edges there, with nodes 4.5e-3 off the circle and the error 6-10x up).
//
// The fix, on the quad-dominant mesh before the split into all quads (the split keeps the angle
// at v): Q = (v, b, c, a) becomes the two triangles (v, b, c) and (v, c, a) — undoing the pairing
// that made it — so v belongs to two cells, and after the split to two quads with about half the
// angle each. Every edge of Q is kept (so the neighbours and every boundary group), the split then
// makes 6 quads of them instead of 4. An edge rotation with a neighbour would only move the
// defect to the next boundary vertex (a valence deficit on a smooth boundary is topological).
// A triangle touching v alone is left (counted): its split gives v one quad with the same angle.
// So is a quad whose split would leave either new angle at v above the bound, and the second flat
// corner of a quad with two (its split serves the first): `found` counts vertices, `split` quads.
#include "mesh/mesh.hpp"

namespace quadapt {

struct BoundaryCornerStats {
  int flat_vertices = 0;  ///< boundary vertices in one cell whose angle there exceeds the bound
  int split = 0;          ///< of those, fixed by splitting their quad into two triangles
};

/// Splits, as above, the quad of every boundary vertex of `m` (quads and triangles,
/// counter-clockwise, conforming; fields and curved geometry are not carried: call before they
/// are attached) that only that quad touches with an angle above `max_angle_deg` there. The new
/// triangle (v, c, a) is appended to m.cells, (v, b, c) takes the quad's index. Deterministic;
/// m's nodes and boundary are unchanged.
BoundaryCornerStats split_flat_boundary_corners(Mesh& m, double max_angle_deg = 150);

}  // namespace quadapt
