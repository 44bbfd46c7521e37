#pragma once
// Per-cell fields carried by a Mesh and written to / read from MSH views.
//
//  CellField      -> $ElementData:      ncomp values per cell (1 = scalar, 9 = 3x3 tensor
//                                       row-major, e.g. the frame "Vinv" with M = V^-1 in the
//                                       upper-left 2x2, zero-padded; docs/design.md §3).
//  CellNodeField  -> $ElementNodeData:  values at `per_cell` points of each cell. For the DG
//                                       solution "u" of degree p: per_cell = (p+1)^2 nodal
//                                       values at the tensor-product Gauss-Lobatto points, index
//                                       i + (p+1)*j with i along xi and j along eta on [-1,1]^2
//                                       (these ARE the DG coefficients of the Lagrange basis).
//                                       `degree` = p marks such a high-order field; the writer
//                                       adds a Gmsh $InterpolationScheme so Gmsh displays it.
//                                       degree = -1: values at the cell's vertices (Gmsh's
//                                       default interpretation).
#include <string>
#include <vector>

namespace quadapt {

struct CellField {
  std::string name;
  int ncomp = 1;
  std::vector<double> values;  ///< #cells * ncomp, cell-major

  double operator()(int cell, int comp = 0) const { return values[static_cast<size_t>(cell) * ncomp + comp]; }
  double& operator()(int cell, int comp = 0) { return values[static_cast<size_t>(cell) * ncomp + comp]; }
  int num_cells() const { return ncomp > 0 ? static_cast<int>(values.size() / ncomp) : 0; }
};

struct CellNodeField {
  std::string name;
  int ncomp = 1;
  int per_cell = 0;   ///< points per cell
  int degree = -1;    ///< DG degree p (per_cell = (p+1)^2 on quads), or -1 for vertex values
  std::vector<double> values;  ///< #cells * per_cell * ncomp, cell-major then point then comp

  const double* cell(int c) const { return values.data() + static_cast<size_t>(c) * per_cell * ncomp; }
  double* cell(int c) { return values.data() + static_cast<size_t>(c) * per_cell * ncomp; }
  int num_cells() const {
    return per_cell * ncomp > 0 ? static_cast<int>(values.size() / (static_cast<size_t>(per_cell) * ncomp)) : 0;
  }
};

}  // namespace quadapt
