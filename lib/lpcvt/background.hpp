#pragma once
// The metric field M(y) of the L_p-CVT generator on its background mesh (thesis §4.1).
//
// The background mesh covers the domain Omega. Each of its cells carries the frame as
// M = V^-1 (CellField "Vinv", 9 components, row-major 3x3, M in the upper-left 2x2; docs/design.md
// §3), so M is piecewise constant; or the metric is an analytic function M(y) (validation
// mode, thesis eq. 6.1). The generator works with the EFFECTIVE metric  M_eff = scale * M :
// a segment u has metric length |M_eff u|, and the L_p-CVT places points one metric unit apart.
//
// Sizes (docs/design.md §4): V = R(theta) diag(h1, h2); the frame's representative parallelogram
// spans +-v, +-w, so the FINAL all-quad mesh should have edges 2 h1 x 2 h2. The final mesh is
// made by recombining lpcvt's triangles into quads (edges = point spacing) and splitting every
// quad into four (halving edges), so the points must be 4 h1 x 4 h2 apart: scale = 1/4, i.e.
// unit metric length = 4 h1 along v (the thesis doubles its size targets for the same reason,
// §4.1). Number of points requested:
//     N = integral over Omega of |det M_eff| dy          (one point per unit metric area).
//
// Integration cells. The energy is integrated over (Voronoi cell) ∩ (integration cell): the
// integration cells are the background cells (a non-convex quad is split into two triangles),
// all convex and counter-clockwise, each with its constant metric or the analytic function.
// With a piecewise-constant metric this integrates each piece with its own constant M, so the
// quadrature is exact (degree-p polynomial) and the gradient is that of the true energy, even
// across the metric's jumps (the thesis's per-facet quadrature was not; its gradients stalled,
// §6.1 Fig. 6.2).
//
// Point location (M at arbitrary points: edge lengths eq. 4.12, inside tests): a uniform grid
// of buckets over the bounding box, each listing the cells whose bounding box overlaps it, plus
// a hint (the previous answer), tested first.
#include <Eigen/Dense>
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "mesh/mesh.hpp"

namespace quadapt {
struct Frame;
}

namespace quadapt::lpcvt {

using Mat2 = Eigen::Matrix2d;

/// An analytic metric y -> M(y) (a 2x2 matrix, not necessarily symmetric) with derivatives.
class AnalyticMetric {
 public:
  virtual ~AnalyticMetric() = default;
  virtual Mat2 M(const Vec2& y) const = 0;
  /// M(y) and its partial derivatives dM/dy0, dM/dy1.
  virtual void eval(const Vec2& y, Mat2& M, Mat2& d0, Mat2& d1) const = 0;
  virtual std::string name() const = 0;
};

/// The saddle metric of thesis eq. 6.1 (Hessian-based, from [40]):
///   M(x, y) = [[1 + 4x^2, -4xy], [-4xy, 1 + 4y^2]],  det M = 1 + 4x^2 + 4y^2.
class SaddleMetric : public AnalyticMetric {
 public:
  Mat2 M(const Vec2& y) const override;
  void eval(const Vec2& y, Mat2& M, Mat2& d0, Mat2& d1) const override;
  std::string name() const override { return "saddle"; }
};

/// A constant metric (tests): M(y) = M0.
class ConstantMetric : public AnalyticMetric {
 public:
  explicit ConstantMetric(const Mat2& m) : m_(m) {}
  Mat2 M(const Vec2&) const override { return m_; }
  void eval(const Vec2&, Mat2& M, Mat2& d0, Mat2& d1) const override {
    M = m_; d0.setZero(); d1.setZero();
  }
  std::string name() const override { return "constant"; }
 private:
  Mat2 m_;
};

/// A convex, counter-clockwise integration cell (a background cell or half of one).
struct IntegrationCell {
  std::array<Vec2, 4> v;  ///< vertices, CCW
  int nv = 4;             ///< 3 or 4
  int mesh_cell = -1;     ///< the background cell it belongs to
  double area = 0;        ///< its area (set by the Background)
  Mat2 M = Mat2::Zero();  ///< effective metric (constant mode; analytic mode: M at centroid)
};

/// True when y is in the closed convex CCW polygon v[0..nv) (within `tol` of its edges).
bool in_convex_polygon(const std::array<Vec2, 4>& v, int nv, const Vec2& y, double tol);

class Background {
 public:
  /// Piecewise-constant metric from a mesh's Vinv taken as it is (no size convention applied):
  /// M_eff = scale * Vinv(cell). Validates the field (frame_from_mesh) and the mesh (cells,
  /// finite coordinates, positive areas). Throws InputError("path: ...") naming the cell at fault.
  static Background from_frame(const Mesh& m, double scale, const std::string& path);
  /// M_eff = scale * f.M (f in the quadapt convention, frame/frame.hpp); reflections kept.
  static Background from_frame(const Frame& f, double scale, const std::string& path = "frame");
  /// Analytic metric M_eff(y) = scale * f(y) over the domain of mesh m (whose cells are used
  /// for integration and point location; fields ignored).
  static Background analytic(const Mesh& m, std::shared_ptr<const AnalyticMetric> f,
                             double scale);
  /// The analytic metric sampled at each cell's centroid: piecewise constant (thesis §6.1,
  /// the "16 x 16 background grid" case).
  static Background sampled(const Mesh& m, const AnalyticMetric& f, double scale);

  /// The same background with M_eff multiplied by f > 0 (metric area times f^2): the coarse
  /// levels of the multilevel start (lpcvt.hpp).
  Background scaled(double f) const;

  /// The effective metric of background (mesh) cell c (its first integration cell's).
  Mat2 mesh_cell_metric(int c) const { return cells_[first_cell_[c]].M; }
  /// Replaces the effective metric of every background cell (frame mode only; one per mesh
  /// cell) and recomputes the metric area (lpcvt/metric_filter.hpp).
  void set_mesh_cell_metrics(const std::vector<Mat2>& M);

  const Mesh& mesh() const { return mesh_; }
  int num_cells() const { return static_cast<int>(cells_.size()); }
  const IntegrationCell& cell(int c) const { return cells_[c]; }
  bool is_analytic() const { return static_cast<bool>(analytic_); }
  double scale() const { return scale_; }

  /// Voronoi cells in the metric (metric_graph.hpp): the partition of integration cell c uses
  /// G_c = (M^T M)^alpha / tr (M^T M)^alpha of its (centroid) metric instead of the identity:
  /// alpha = 1 the metric's own cells, 0 Euclidean cells (the thesis's), between: the
  /// anisotropy of the cells is the metric's to the power alpha. Off by default; the frame
  /// defaults turn it on (lpcvt --cells, --cell-anisotropy).
  void set_metric_cells(bool on, double alpha = 1.0) {
    metric_cells_ = on;
    cell_alpha_ = alpha;
    cache_partition();
  }
  bool metric_cells() const { return metric_cells_; }
  double cell_anisotropy() const { return cell_alpha_; }
  /// The partition metric of integration cell c: G_c (above) or the identity (cached: the
  /// energy asks for it once per piece).
  Mat2 partition_metric(int c) const { return metric_cells_ ? partition_[c] : Mat2::Identity(); }

  /// M_eff at y, y in integration cell c.
  Mat2 metric(int c, const Vec2& y) const;
  /// M_eff and its derivatives at y in cell c (zero derivatives in constant mode).
  void metric_derivs(int c, const Vec2& y, Mat2& M, Mat2& d0, Mat2& d1) const;

  /// Integration cell containing y (boundary included, with a relative tolerance), or -1.
  /// `hint`: a cell to test first (e.g. the previous answer).
  int locate(const Vec2& y, int hint = -1) const;
  /// The same contract as locate, for a y near `hint` (e.g. the previous answer of a spatially
  /// ordered sequence): walks from the hint across the cells' shared edges (at most 12 steps,
  /// towards the edge y is farthest outside of), then searches the buckets. Where y lies on an
  /// edge shared by two cells (within the tolerance), the cell found may differ from locate's.
  int locate_near(const Vec2& y, int hint) const;
  /// True when y lies in the closed domain.
  bool inside(const Vec2& y) const { return locate(y) >= 0; }

  /// Area of the domain (sum of cell areas).
  double area() const { return area_; }
  /// integral of |det M_eff| over the domain (Gauss quadrature in analytic mode): the number
  /// of points the metric asks for (one per unit metric area).
  double metric_area() const { return metric_area_; }
  /// Bounding box.
  Vec2 lo() const { return lo_; }
  Vec2 hi() const { return hi_; }
  /// A length scale: sqrt(area / max(1, metric_area)), the mean point spacing asked for.
  double mean_spacing() const;

 private:
  void build(const Mesh& m);  // integration cells, bbox, locator
  void finish();              // areas, metric area, partition metrics
  void cache_partition();     // partition_ from the cells' metrics (metric cells only)

  Mesh mesh_;
  std::vector<IntegrationCell> cells_;
  std::vector<int> first_cell_;  ///< per mesh cell: its first integration cell
  std::shared_ptr<const AnalyticMetric> analytic_;
  double scale_ = 1;
  bool metric_cells_ = false;
  double cell_alpha_ = 1.0;
  std::vector<Mat2> partition_;  ///< per integration cell: G_c (metric cells only)
  double area_ = 0, metric_area_ = 0;
  Vec2 lo_{0, 0}, hi_{0, 0};
  // locator: nx*ny buckets, CSR lists of cells
  int nx_ = 1, ny_ = 1;
  double dx_ = 1, dy_ = 1, tol_ = 0;
  std::vector<int> bucket_ptr_, bucket_cells_;
  // crowded buckets (> 16 cells): an n x n grid of sub-buckets, CSR from sub_ptr_[first]
  struct Sub {
    int n, first;
  };
  std::vector<int> bucket_sub_;  ///< per bucket: index into subs_, or -1
  std::vector<Sub> subs_;
  std::vector<int> sub_ptr_, sub_cells_;
  std::vector<std::array<int, 4>> across_;  ///< per integration cell and edge k (v[k] -> v[k+1]): the
                                            ///< cell sharing that edge (same end points), or -1
  int locate_buckets(const Vec2& y) const;
};


}  // namespace quadapt::lpcvt
