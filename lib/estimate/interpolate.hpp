#pragma once
// Nodal interpolation of a function into a DG field of degree p (the "u" CellNodeField layout:
// (p+1)^2 values per quad at the tensor GLL points, index i + (p+1) j, i along xi). Used by the
// estimator's tests and by benchmarks that estimate frames from an exact solution.
#include <functional>
#include <string>

#include "mesh/mesh.hpp"

namespace quadapt {

/// Interpolates f(x, y) at the GLL nodes of every cell of the all-quad mesh m.
/// Throws InputError for a mesh with triangles or p < 0.
CellNodeField interpolate_dg(const Mesh& m, int p, const std::function<double(double, double)>& f,
                             const std::string& name = "u");

}  // namespace quadapt
