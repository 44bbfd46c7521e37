#pragma once
// The frame field: the one contract between the error estimator (size-solve) and the mesh
// generators (lpcvt, bamgquad), and the reference of meshquality, quadsmooth and meshplot
// (thesis eqs. 3.11-3.13, 5.1; docs/file-formats.md, "Frame files").
//
// Per background cell, V = R(θ) diag(h1, h2) with columns v (long axis, along θ) and w, and
// M = V^-1 = diag(1/h1, 1/h2) R(-θ) (eq. 3.13); the Riemannian metric is M^T M. On file, "Vinv"
// is a cell field of 9 components: the row-major 3x3 with M in the upper-left 2x2, zero-padded
// (the layout PHiLiP writes).
//
// Size conventions. Two scales of M describe the same target mesh:
//   quadapt: v, w are HALF-axes: the target cell spans ±v, ±w, edges 2h1 x 2h2, density
//            d = |det M| / 4 cells per unit area (eq. 5.1 with d = 1/(4h^2));
//   philip:  v, w are the full edges (PHiLiP's files): d = |det M_philip|, M = 2 M_philip.
// quadapt writes the word "quadapt" in a section $FrameConvention of every frame file; a file
// without the section (PHiLiP's) is read as philip. A Frame holds M in the quadapt convention
// whatever the file's, so the factors 2 and 4 of the conventions appear in this file only.
//
// Reflections: PHiLiP writes some cells with det M < 0 (a reflection; M^T M is the same).
// Frame::M keeps them as read (the L_p-CVT energy only sees |M u|); oriented() removes them.
#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/atomic_file.hpp"
#include "mesh/locate.hpp"
#include "mesh/mesh.hpp"

namespace quadapt {

using Mat2 = Eigen::Matrix2d;

enum class SizeConvention { Quadapt, Philip };

/// "quadapt" / "philip".
std::string to_string(SizeConvention c);
/// Parses "quadapt" / "philip"; throws InputError(source, ...) otherwise.
SizeConvention parse_size_convention(const std::string& word, const std::string& source = "");
/// The factor taking a file's M to the quadapt convention: 1 (quadapt), 2 (philip).
double quadapt_factor(SizeConvention c);
/// The convention the mesh's file states ($FrameConvention), philip when it states none.
SizeConvention stated_convention(const Mesh& m, const std::string& path = "");

/// Target cells per unit area for the size h = sqrt(h1 h2) (quadapt convention): d = 1/(4 h^2), eq. 5.1.
double cell_density(double h);
/// The size h of a cell density d: h = 1 / (2 sqrt(d)).
double size_for_density(double d);

/// M = diag(1/h1, 1/h2) R(-θ) for h = sqrt(h1 h2), ρ = h1/h2 (quadapt convention, eq. 3.13).
Mat2 frame_inverse(double h, double rho, double theta);
/// The 9 row-major components of the zero-padded 3x3 with M in the upper-left 2x2.
std::array<double, 9> vinv_components(const Mat2& M);
/// M with its reflection removed: the second row negated when det M < 0 (same M^T M).
Mat2 without_reflection(const Mat2& M);
/// The frame's axes (columns of V = M^-1: v, w). Throws NumericalError when M is singular.
std::pair<Vec2, Vec2> frame_axes(const Mat2& M);

/// A frame on its background mesh, in the quadapt convention.
struct Frame {
  Mesh mesh;                      ///< background: geometry, boundary groups, fields as read
  std::vector<Mat2> M;            ///< per cell, quadapt convention, reflections as read
  SizeConvention source = SizeConvention::Quadapt;  ///< the convention M was converted from

  int num_cells() const { return static_cast<int>(M.size()); }
  /// M of every cell without reflections (det > 0).
  std::vector<Mat2> oriented() const;
  /// The metric in which a target cell's edge has length 1: M / 2 (a cell edge e measures
  /// |cell_metric e|; the number of target cells is the integral of |det cell_metric|).
  Mat2 cell_metric(int c) const { return cell_metric_factor() * M[c]; }
  /// The factor of cell_metric: 1/2 (the target cell spans ±v, ±w).
  static double cell_metric_factor();
  /// Continuous number of target cells: sum over cells of area |det M| / 4 (eq. 5.1).
  double target_cells() const;
  /// The same frame with M multiplied by f > 0 (target_cells times f^2).
  Frame scaled(double f) const;
  /// The factor f for which scaled(f) asks for `cells` target cells: sqrt(cells / target_cells()).
  double scale_for_cells(double cells) const;
  /// Per cell of m: the oriented M of the frame cell containing the cell's centroid (the nearest
  /// frame cell for a centroid outside, counted in *outside).
  std::vector<Mat2> at_cells(const Mesh& m, int* outside = nullptr) const;
};

/// Target cells of a complexity C in degrees of freedom at DG degree p: C / (p+1)^2.
double cells_for_complexity(double complexity, int degree);

/// The frame of a mesh with the cell field "Vinv". `convention` overrides what the mesh states
/// (stated_convention). Validates: the field present with 9 components and one value per cell,
/// every M finite and non-singular. Throws InputError("path: ...") naming the cell at fault.
Frame frame_from_mesh(const Mesh& m, const std::string& path, std::optional<SizeConvention> convention = {});
/// Reads and validates a frame file (read_valid_msh + frame_from_mesh), then puts the frame in
/// the canonical order of mesh/canonical.hpp: a renumbered file gives the same Frame, so the
/// tools' outputs do not depend on the file's numbering (validation messages name the file's
/// own cell numbers).
Frame read_frame(const std::string& path, std::optional<SizeConvention> convention = {});
/// The frame with its background in the canonical order of mesh/canonical.hpp (cells and M
/// renumbered together): what read_frame returns. A library caller whose frame never went
/// through a file gets the tools' results byte for byte with it (lpcvt, quadsmooth read their
/// frames with read_frame).
Frame canonical_frame(Frame f);

/// Sets the field "Vinv" (quadapt convention) and the $FrameConvention tag of m.
void set_frame_field(Mesh& m, const std::vector<Mat2>& M);
/// The frame's background without other fields, with Vinv and its tag: what write_frame writes.
Mesh frame_mesh(const Frame& f);
/// Writes frame_mesh(f) atomically.
void write_frame(const Frame& f, const std::string& path);
/// The same staged in `batch` (io/msh.hpp's write_msh).
void write_frame(const Frame& f, const std::string& path, OutputBatch& batch);

/// M at a point: the frame's M (oriented) of the background cell containing x — on an edge or a
/// vertex shared by cells, the finest of them (largest |det M|, then the lowest index), a choice
/// that turns and mirrors with the frame unless two different M there have exactly equal |det| —
/// or of the nearest cell when x lies outside (equally near cells: the lowest index). Holds a
/// reference to the frame. Throws InputError when the frame has no cells or not one M per
/// background cell.
class FrameSampler {
 public:
  explicit FrameSampler(const Frame& f);
  /// The background cell used for x, and whether x lies inside the background.
  int cell(const Vec2& x, bool* inside = nullptr) const;
  /// Piecewise-constant M (oriented) at x.
  Mat2 at(const Vec2& x, bool* inside = nullptr) const { return oriented_[cell(x, inside)]; }
  /// The same, for a point that moves a little between calls: `hint` (in/out; -1 at first) is
  /// the cell of the last call, kept while x is well inside it (CellLocator::well_inside).
  Mat2 at(const Vec2& x, int& hint) const {
    if (!locator_.well_inside(hint, x)) hint = cell(x);
    return oriented_[hint];
  }

 private:
  std::vector<Mat2> oriented_;
  CellLocator locator_;
};

}  // namespace quadapt
