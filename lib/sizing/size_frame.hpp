#pragma once
// The frame written for the mesh generators from a size field (thesis eqs. 3.11-3.13): per cell
// M = frame_inverse(h, ρ, θ) in the quadapt convention (frame/frame.hpp).
#include "mesh/mesh.hpp"
#include "sizing/size_field.hpp"

namespace quadapt {

/// FRAME mesh: shape's geometry and boundary groups, no input fields, plus CellFields
/// "Vinv" (9 comps, with its convention tag), "h", "theta", "rho" (and "alpha" in goal mode).
Mesh make_frame_mesh(const Mesh& shape, const SizeResult& r);

}  // namespace quadapt
