#pragma once
// Subdivision of a quad-dominant mesh into an all-quad mesh (thesis §4.6, "split to all-quad").
//
// Every edge gets its exact midpoint (shared by both neighbours), every cell its centre (the
// vertex average: the bilinear centre of a quad, the centroid of a triangle). A quad
// (v0 v1 v2 v3) becomes the 4 quads (v_i, m_{i,i+1}, centre, m_{i-1,i}); a triangle becomes 3
// quads the same way. Counter-clockwise cells give counter-clockwise children; edge lengths
// are halved, so a mesh meant to have edges of length L must be generated with edges 2L.
// Boundary edges are split in two, both halves keeping the group. Node order: the input's
// nodes (unchanged indices), then edge midpoints, then cell centres. Fields are dropped (the
// cells are new); groups, domain name and tag are kept.
#include "mesh/mesh.hpp"

namespace quadapt {

/// Splits every cell; the input must be conforming (no hanging nodes).
Mesh split_to_all_quads(const Mesh& m);

}  // namespace quadapt
