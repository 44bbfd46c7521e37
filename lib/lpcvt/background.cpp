#include "lpcvt/background.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <tuple>

#include "core/error.hpp"
#include "frame/frame.hpp"
#include "fem/quadrature.hpp"
#include "mesh/label.hpp"
#include "mesh/topology.hpp"

namespace quadapt::lpcvt {

namespace {

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

}  // namespace

bool in_convex_polygon(const std::array<Vec2, 4>& v, int nv, const Vec2& y, double tol) {
  for (int k = 0; k < nv; ++k) {
    const Vec2& a = v[k];
    const Vec2& b = v[(k + 1) % nv];
    const Vec2 e = b - a;
    // cross < -tol |e|, without the square root
    const double c = cross(e, y - a);
    if (c < 0 && c * c > tol * tol * e.squaredNorm()) return false;
  }
  return true;
}

// ------------------------------------------------------------------------------ metrics

Mat2 SaddleMetric::M(const Vec2& y) const {
  Mat2 m;
  m << 1 + 4 * y.x() * y.x(), -4 * y.x() * y.y(), -4 * y.x() * y.y(), 1 + 4 * y.y() * y.y();
  return m;
}

void SaddleMetric::eval(const Vec2& y, Mat2& M, Mat2& d0, Mat2& d1) const {
  M = this->M(y);
  d0 << 8 * y.x(), -4 * y.y(), -4 * y.y(), 0;
  d1 << 0, -4 * y.x(), -4 * y.x(), 8 * y.y();
}

// ------------------------------------------------------------------------------ construction

void Background::build(const Mesh& m) {
  mesh_ = m;
  cells_.clear();
  if (m.num_cells() == 0) throw InputError("", "background mesh has no cells");
  for (const Vec2& p : m.nodes)
    if (!std::isfinite(p.x()) || !std::isfinite(p.y()))
      throw InputError("", "background mesh has a non-finite node coordinate");
  lo_ = hi_ = m.nodes.empty() ? Vec2(0, 0) : m.nodes[0];
  for (const Vec2& p : m.nodes) {
    lo_ = lo_.cwiseMin(p);
    hi_ = hi_.cwiseMax(p);
  }
  const double diam = (hi_ - lo_).norm();
  tol_ = 1e-10 * diam;
  first_cell_.assign(m.num_cells(), -1);
  for (int c = 0; c < m.num_cells(); ++c) {
    first_cell_[c] = static_cast<int>(cells_.size());
    const Cell& cl = m.cells[c];
    if (cl.nv != 3 && cl.nv != 4) throw InputError("", "background " + cell_label(m, c) + " is neither a triangle nor a quad");
    for (int k = 0; k < cl.nv; ++k)
      if (cl.v[k] < 0 || cl.v[k] >= m.num_nodes())
        throw InputError("", "background cell " + number_text(c) + " has a node index out of range");
    std::array<Vec2, 4> v;
    for (int k = 0; k < cl.nv; ++k) v[k] = m.nodes[cl.v[k]];
    double a = cell_area(m, c);
    if (!(a > 1e-14 * diam * diam))
      throw InputError("", "background " + cell_label(m, c) + (a < 0 ? " is inverted (clockwise)" : " is degenerate (zero area)"));
    int reflex = -1;
    for (int k = 0; k < cl.nv; ++k) {
      double t = cross(v[k] - v[(k + cl.nv - 1) % cl.nv], v[(k + 1) % cl.nv] - v[k]);
      if (t <= 0) {
        if (reflex >= 0 || cl.nv == 3)
          throw InputError("", "background " + cell_label(m, c) + " is inverted or self-intersecting");
        reflex = k;
      }
    }
    if (reflex < 0) {
      IntegrationCell ic;
      ic.v = v;
      ic.nv = cl.nv;
      ic.mesh_cell = c;
      cells_.push_back(ic);
    } else {  // non-convex quad: split along the diagonal from the reflex vertex
      for (int h = 0; h < 2; ++h) {
        IntegrationCell ic;
        ic.nv = 3;
        ic.mesh_cell = c;
        int k0 = reflex, k1 = (reflex + 1 + h) % 4, k2 = (reflex + 2 + h) % 4;
        ic.v = {v[k0], v[k1], v[k2], Vec2(0, 0)};
        cells_.push_back(ic);
      }
    }
  }
  // A mesh without boundary edges (e.g. built in memory): its free edges, one group.
  if (mesh_.boundary.empty()) {
    Topology t = build_topology(mesh_);
    int g = mesh_.group_index("boundary");
    for (const Face& f : t.faces) {
      if (!f.is_boundary()) continue;
      const Cell& cl = mesh_.cells[f.cell[0]];
      BoundaryEdge be;
      be.v = {cl.v[f.local_edge[0]], cl.v[(f.local_edge[0] + 1) % cl.nv]};
      be.group = g;
      mesh_.boundary.push_back(be);
    }
  }
  // Cell adjacency (locate_near's walk): edges matched by their end points' coordinates.
  const int n = static_cast<int>(cells_.size());
  {
    struct End {
      double ax, ay, bx, by;
      int cell, edge;
    };
    std::vector<End> ends;
    ends.reserve(4 * static_cast<size_t>(n));
    for (int c = 0; c < n; ++c)
      for (int k = 0; k < cells_[c].nv; ++k) {
        Vec2 a = cells_[c].v[k], b = cells_[c].v[(k + 1) % cells_[c].nv];
        if (std::make_pair(b.x(), b.y()) < std::make_pair(a.x(), a.y())) std::swap(a, b);
        ends.push_back({a.x(), a.y(), b.x(), b.y(), c, k});
      }
    auto key = [](const End& e) { return std::make_tuple(e.ax, e.ay, e.bx, e.by); };
    std::sort(ends.begin(), ends.end(), [&](const End& l, const End& r) {
      return key(l) != key(r) ? key(l) < key(r) : std::make_pair(l.cell, l.edge) < std::make_pair(r.cell, r.edge);
    });
    across_.assign(n, {-1, -1, -1, -1});
    for (size_t k = 0; k + 1 < ends.size(); ++k)
      if (key(ends[k]) == key(ends[k + 1]) && (k + 2 == ends.size() || key(ends[k + 2]) != key(ends[k]))) {
        across_[ends[k].cell][ends[k].edge] = ends[k + 1].cell;
        across_[ends[k + 1].cell][ends[k + 1].edge] = ends[k].cell;
      }
  }
  // Bucket grid: about one cell per bucket.
  Vec2 ext = (hi_ - lo_).cwiseMax(Vec2::Constant(1e-300));
  double aspect = ext.x() / ext.y();
  nx_ = std::clamp(static_cast<int>(std::ceil(std::sqrt(n * aspect))), 1, 4096);
  ny_ = std::clamp(static_cast<int>(std::ceil(n / static_cast<double>(nx_))), 1, 4096);
  dx_ = ext.x() / nx_;
  dy_ = ext.y() / ny_;
  std::vector<std::vector<int>> b(static_cast<size_t>(nx_) * ny_);
  for (int c = 0; c < n; ++c) {
    Vec2 a = cells_[c].v[0], z = a;
    for (int k = 1; k < cells_[c].nv; ++k) {
      a = a.cwiseMin(cells_[c].v[k]);
      z = z.cwiseMax(cells_[c].v[k]);
    }
    int i0 = std::clamp(static_cast<int>(std::floor((a.x() - tol_ - lo_.x()) / dx_)), 0, nx_ - 1);
    int i1 = std::clamp(static_cast<int>(std::floor((z.x() + tol_ - lo_.x()) / dx_)), 0, nx_ - 1);
    int j0 = std::clamp(static_cast<int>(std::floor((a.y() - tol_ - lo_.y()) / dy_)), 0, ny_ - 1);
    int j1 = std::clamp(static_cast<int>(std::floor((z.y() + tol_ - lo_.y()) / dy_)), 0, ny_ - 1);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) b[static_cast<size_t>(j) * nx_ + i].push_back(c);
  }
  bucket_ptr_.assign(b.size() + 1, 0);
  for (size_t k = 0; k < b.size(); ++k) bucket_ptr_[k + 1] = bucket_ptr_[k] + static_cast<int>(b[k].size());
  bucket_cells_.clear();
  bucket_cells_.reserve(bucket_ptr_.back());
  for (auto& l : b) bucket_cells_.insert(bucket_cells_.end(), l.begin(), l.end());
  // Graded backgrounds (boundary layers, shocks) put hundreds of cells in one bucket where the
  // sites are densest: such buckets get an s x s grid of their own (the same cells in the same
  // order, so locate's answer does not change).
  bucket_sub_.assign(b.size(), -1);
  subs_.clear();
  sub_ptr_.assign(1, 0);
  sub_cells_.clear();
  for (size_t k = 0; k < b.size(); ++k) {
    if (b[k].size() <= 16) continue;
    const int sn = std::min(64, static_cast<int>(std::ceil(std::sqrt(static_cast<double>(b[k].size())))));
    const int bi = static_cast<int>(k % nx_), bj = static_cast<int>(k / nx_);
    bucket_sub_[k] = static_cast<int>(subs_.size());
    subs_.push_back({sn, static_cast<int>(sub_ptr_.size()) - 1});
    std::vector<std::vector<int>> sb(static_cast<size_t>(sn) * sn);
    for (int c : b[k]) {
      Vec2 a = cells_[c].v[0], z = a;
      for (int q = 1; q < cells_[c].nv; ++q) {
        a = a.cwiseMin(cells_[c].v[q]);
        z = z.cwiseMax(cells_[c].v[q]);
      }
      auto sub = [&](double t, int base, int lim) {
        return std::clamp(static_cast<int>(std::floor((t - base) * sn)), 0, lim);
      };
      const int i0 = sub((a.x() - tol_ - lo_.x()) / dx_, bi, sn - 1), i1 = sub((z.x() + tol_ - lo_.x()) / dx_, bi, sn - 1);
      const int j0 = sub((a.y() - tol_ - lo_.y()) / dy_, bj, sn - 1), j1 = sub((z.y() + tol_ - lo_.y()) / dy_, bj, sn - 1);
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) sb[static_cast<size_t>(j) * sn + i].push_back(c);
    }
    for (auto& l : sb) {
      sub_cells_.insert(sub_cells_.end(), l.begin(), l.end());
      sub_ptr_.push_back(static_cast<int>(sub_cells_.size()));
    }
  }
}

void Background::finish() {
  area_ = 0;
  metric_area_ = 0;
  const TriangleRule& rule = collapsed_gauss(8);
  for (IntegrationCell& ic : cells_) {
    ic.area = 0;
    for (int t = 1; t + 1 < ic.nv; ++t) {
      const Vec2 &a = ic.v[0], &b = ic.v[t], &c = ic.v[t + 1];
      double at = 0.5 * cross(b - a, c - a);
      ic.area += at;
      area_ += at;
      if (!analytic_) {
        metric_area_ += at * std::abs(ic.M.determinant());
      } else {
        double s = 0;
        for (int q = 0; q < rule.size(); ++q) {
          Vec2 y = rule.bary[q][0] * a + rule.bary[q][1] * b + rule.bary[q][2] * c;
          s += rule.w[q] * std::abs(analytic_->M(y).determinant());
        }
        metric_area_ += at * s * scale_ * scale_;
      }
    }
  }
  cache_partition();
}

Background Background::from_frame(const Frame& f, double scale, const std::string& path) {
  if (!(scale > 0) || !std::isfinite(scale)) throw InputError("", "metric scale must be positive");
  Background bg;
  try {
    bg.build(f.mesh);
  } catch (const InputError& e) {
    throw InputError(path, e.what());
  }
  bg.scale_ = scale;
  // without PHiLiP's reflections (det M < 0; the same M^T M): a reflected frame meshes as its
  // unreflected twin, byte for byte (the lattice start and the filters see M itself)
  const std::vector<Mat2> oriented = f.oriented();
  for (IntegrationCell& ic : bg.cells_) ic.M = scale * oriented[ic.mesh_cell];
  bg.finish();
  return bg;
}

Background Background::from_frame(const Mesh& m, double scale, const std::string& path) {
  return from_frame(frame_from_mesh(m, path, SizeConvention::Quadapt), scale, path);
}

Background Background::analytic(const Mesh& m, std::shared_ptr<const AnalyticMetric> f, double scale) {
  Background bg;
  bg.build(m);
  bg.scale_ = scale;
  bg.analytic_ = std::move(f);
  for (IntegrationCell& ic : bg.cells_) {
    Vec2 g = Vec2::Zero();
    for (int k = 0; k < ic.nv; ++k) g += ic.v[k] / ic.nv;
    ic.M = scale * bg.analytic_->M(g);
  }
  bg.finish();
  return bg;
}

Background Background::sampled(const Mesh& m, const AnalyticMetric& f, double scale) {
  Background bg;
  bg.build(m);
  bg.scale_ = scale;
  for (IntegrationCell& ic : bg.cells_) ic.M = scale * f.M(cell_centroid(m, ic.mesh_cell));
  bg.finish();
  return bg;
}

void Background::set_mesh_cell_metrics(const std::vector<Mat2>& M) {
  if (analytic_) throw InputError("", "metric filters need a piecewise-constant metric");
  if (static_cast<int>(M.size()) != mesh_.num_cells()) throw InputError("", "one metric per background cell expected");
  for (IntegrationCell& ic : cells_) ic.M = M[ic.mesh_cell];
  finish();
}

void Background::cache_partition() {
  partition_.clear();
  if (!metric_cells_) return;
  partition_.resize(cells_.size());
  for (size_t c = 0; c < cells_.size(); ++c) {
    const Mat2 G = cells_[c].M.transpose() * cells_[c].M;
    if (cell_alpha_ == 1.0) {
      partition_[c] = G / G.trace();
      continue;
    }
    Eigen::SelfAdjointEigenSolver<Mat2> es(G);
    const Eigen::Vector2d l = es.eigenvalues().cwiseMax(1e-300).array().pow(cell_alpha_);
    const Mat2 Ga = es.eigenvectors() * l.asDiagonal() * es.eigenvectors().transpose();
    partition_[c] = Ga / Ga.trace();
  }
}

Background Background::scaled(double f) const {
  if (!(f > 0) || !std::isfinite(f)) throw InputError("", "metric scale factor must be positive");
  Background b = *this;
  b.scale_ *= f;
  for (IntegrationCell& ic : b.cells_) ic.M *= f;
  b.metric_area_ *= f * f;
  b.cache_partition();
  return b;
}

// ------------------------------------------------------------------------------ queries

Mat2 Background::metric(int c, const Vec2& y) const {
  if (analytic_) return scale_ * analytic_->M(y);
  return cells_[c].M;
}

void Background::metric_derivs(int c, const Vec2& y, Mat2& M, Mat2& d0, Mat2& d1) const {
  if (analytic_) {
    analytic_->eval(y, M, d0, d1);
    M *= scale_;
    d0 *= scale_;
    d1 *= scale_;
  } else {
    M = cells_[c].M;
    d0.setZero();
    d1.setZero();
  }
}

int Background::locate(const Vec2& y, int hint) const {
  if (hint >= 0 && hint < num_cells() && in_convex_polygon(cells_[hint].v, cells_[hint].nv, y, tol_))
    return hint;
  return locate_buckets(y);
}

int Background::locate_near(const Vec2& y, int hint) const {
  if (hint < 0 || hint >= num_cells()) return locate_buckets(y);
  int c = hint;
  for (int step = 0; step < 12; ++step) {
    const IntegrationCell& ic = cells_[c];
    // in_convex_polygon's test, and the edge whose line y is farthest outside of (in distance)
    int best = -1;
    double worst = 0;
    bool inside = true;
    for (int k = 0; k < ic.nv; ++k) {
      const Vec2 e = ic.v[(k + 1) % ic.nv] - ic.v[k];
      const double d = cross(e, y - ic.v[k]), e2 = e.squaredNorm();
      if (d < 0 && d * d > tol_ * tol_ * e2) inside = false;
      if (d < 0 && d * d > worst * e2) {
        worst = d * d / e2;
        best = k;
      }
    }
    if (inside) return c;
    if (best < 0 || across_[c][best] < 0) break;
    c = across_[c][best];
  }
  return locate_buckets(y);
}

int Background::locate_buckets(const Vec2& y) const {
  double fx = (y.x() - lo_.x()) / dx_, fy = (y.y() - lo_.y()) / dy_;
  if (!(fx > -1e-9 * nx_ - 1e-9 && fy > -1e-9 * ny_ - 1e-9 && fx < nx_ * (1 + 1e-9) + 1e-9 &&
        fy < ny_ * (1 + 1e-9) + 1e-9))
    return -1;
  int i = std::clamp(static_cast<int>(std::floor(fx)), 0, nx_ - 1);
  int j = std::clamp(static_cast<int>(std::floor(fy)), 0, ny_ - 1);
  size_t b = static_cast<size_t>(j) * nx_ + i;
  if (bucket_sub_[b] >= 0) {
    const Sub& sg = subs_[bucket_sub_[b]];
    const int si = std::clamp(static_cast<int>(std::floor((fx - i) * sg.n)), 0, sg.n - 1);
    const int sj = std::clamp(static_cast<int>(std::floor((fy - j) * sg.n)), 0, sg.n - 1);
    const int k = sg.first + sj * sg.n + si;
    for (int q = sub_ptr_[k]; q < sub_ptr_[k + 1]; ++q) {
      const int c = sub_cells_[q];
      if (in_convex_polygon(cells_[c].v, cells_[c].nv, y, tol_)) return c;
    }
    return -1;
  }
  for (int k = bucket_ptr_[b]; k < bucket_ptr_[b + 1]; ++k) {
    int c = bucket_cells_[k];
    if (in_convex_polygon(cells_[c].v, cells_[c].nv, y, tol_)) return c;
  }
  return -1;
}

double Background::mean_spacing() const { return std::sqrt(area_ / std::max(1.0, metric_area_)); }

}  // namespace quadapt::lpcvt
