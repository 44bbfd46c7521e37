#include "mesh/locate.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace quadapt {

CellLocator::CellLocator(const Mesh& m) : m_(m) {
  Vec2 hi(-INFINITY, -INFINITY);
  lo_ = Vec2(INFINITY, INFINITY);
  for (const Cell& c : m.cells)
    for (int i = 0; i < c.nv; ++i) {
      lo_ = lo_.cwiseMin(m.nodes[c.v[i]]);
      hi = hi.cwiseMax(m.nodes[c.v[i]]);
    }
  if (m.cells.empty()) {
    lo_ = hi = Vec2(0, 0);
  }
  const Vec2 ext = (hi - lo_).cwiseMax(Vec2(1e-300, 1e-300));
  const double n = std::max(1.0, std::sqrt(static_cast<double>(m.num_cells())));
  const double aspect = ext.x() / ext.y();
  nx_ = std::clamp(static_cast<int>(std::ceil(n * std::sqrt(aspect))), 1, 4096);
  ny_ = std::clamp(static_cast<int>(std::ceil(n / std::sqrt(aspect))), 1, 4096);
  cell_size_ = Vec2(ext.x() / nx_, ext.y() / ny_);
  buckets_.assign(static_cast<size_t>(nx_) * ny_, {});
  std::vector<std::array<Vec2, 2>> box(m.num_cells());  // each cell's bounding box
  for (int c = 0; c < m.num_cells(); ++c) {
    const Cell& cell = m.cells[c];
    Vec2 a = m.nodes[cell.v[0]], b = a;
    for (int i = 1; i < cell.nv; ++i) {
      a = a.cwiseMin(m.nodes[cell.v[i]]);
      b = b.cwiseMax(m.nodes[cell.v[i]]);
    }
    box[c] = {a, b};
    for (int j = by(a.y()); j <= by(b.y()); ++j)
      for (int i = bx(a.x()); i <= bx(b.x()); ++i) buckets_[static_cast<size_t>(j) * nx_ + i].push_back(c);
  }
  // crowded buckets: a sub-grid each (cells pushed in ascending order, so each list is sorted)
  bucket_sub_.assign(buckets_.size(), -1);
  for (size_t bk = 0; bk < buckets_.size(); ++bk) {
    const std::vector<int>& list = buckets_[bk];
    if (static_cast<int>(list.size()) <= kCrowded) continue;
    Sub sub;
    sub.n = std::min(64, static_cast<int>(std::ceil(std::sqrt(static_cast<double>(list.size())))));
    sub.first = sub_.size();
    sub.lo = lo_ + Vec2((bk % nx_) * cell_size_.x(), (bk / nx_) * cell_size_.y());
    sub.size = cell_size_ / sub.n;
    bucket_sub_[bk] = static_cast<int>(subs_.size());
    subs_.push_back(sub);
    sub_.resize(sub_.size() + static_cast<size_t>(sub.n) * sub.n);
    for (int c : list) {
      const auto& [a, b] = box[c];
      for (int j = sub.index(a, 1); j <= sub.index(b, 1); ++j)
        for (int i = sub.index(a, 0); i <= sub.index(b, 0); ++i)
          sub_[sub.first + static_cast<size_t>(j) * sub.n + i].push_back(c);
    }
  }
}

int CellLocator::Sub::index(const Vec2& x, int axis) const {
  return std::clamp(static_cast<int>(std::floor((x[axis] - lo[axis]) / size[axis])), 0, n - 1);
}

const std::vector<int>& CellLocator::candidates(size_t b, const Vec2& x) const {
  const int s = bucket_sub_[b];
  if (s < 0) return buckets_[b];
  const Sub& sub = subs_[s];
  return sub_[sub.first + static_cast<size_t>(sub.index(x, 1)) * sub.n + sub.index(x, 0)];
}

int CellLocator::bx(double x) const { return std::clamp(static_cast<int>(std::floor((x - lo_.x()) / cell_size_.x())), 0, nx_ - 1); }
int CellLocator::by(double y) const { return std::clamp(static_cast<int>(std::floor((y - lo_.y()) / cell_size_.y())), 0, ny_ - 1); }

bool CellLocator::inside(int c, const Vec2& x) const {
  // Crossing number on the closed polygon, with points on an edge counted as inside.
  const Cell& cell = m_.cells[c];
  bool in = false;
  for (int i = 0, j = cell.nv - 1; i < cell.nv; j = i++) {
    const Vec2& a = m_.nodes[cell.v[i]];
    const Vec2& b = m_.nodes[cell.v[j]];
    const Vec2 ab = b - a, ax = x - a;
    const double cr = ab.x() * ax.y() - ab.y() * ax.x();
    const double len2 = ab.squaredNorm();
    if (std::abs(cr) <= 1e-14 * len2 && ax.dot(ab) >= 0 && ax.dot(ab) <= len2) return true;
    if ((a.y() > x.y()) != (b.y() > x.y()) && x.x() < a.x() + (x.y() - a.y()) * ab.x() / ab.y()) in = !in;
  }
  return in;
}

double CellLocator::distance(int c, const Vec2& x) const {
  const Cell& cell = m_.cells[c];
  double d = INFINITY;
  for (int i = 0; i < cell.nv; ++i) {
    d = std::min(d, segment_distance(x, m_.nodes[cell.v[i]], m_.nodes[cell.v[(i + 1) % cell.nv]]));
  }
  return d;
}

bool CellLocator::well_inside(int c, const Vec2& x) const {
  if (c < 0 || c >= static_cast<int>(m_.cells.size())) return false;
  const Cell& cell = m_.cells[c];
  for (int i = 0; i < cell.nv; ++i) {
    const Vec2& a = m_.nodes[cell.v[i]];
    const Vec2 ab = m_.nodes[cell.v[(i + 1) % cell.nv]] - a, ax = x - a;
    if (!(ab.x() * ax.y() - ab.y() * ax.x() > 1e-9 * ab.squaredNorm())) return false;
  }
  return true;
}

const std::vector<int>* CellLocator::candidates_of(const Vec2& x) const {
  if (m_.cells.empty()) return nullptr;
  const double fx = (x.x() - lo_.x()) / cell_size_.x(), fy = (x.y() - lo_.y()) / cell_size_.y();
  if (fx < -1e-9 || fy < -1e-9 || fx > nx_ + 1e-9 || fy > ny_ + 1e-9) return nullptr;
  return &candidates(static_cast<size_t>(by(x.y())) * nx_ + bx(x.x()), x);
}

int CellLocator::locate(const Vec2& x) const {
  if (const std::vector<int>* cs = candidates_of(x))
    for (int c : *cs)
      if (inside(c, x)) return c;
  return -1;
}

void CellLocator::locate_all(const Vec2& x, std::vector<int>& out) const {
  out.clear();
  if (const std::vector<int>* cs = candidates_of(x))
    for (int c : *cs)
      if (inside(c, x)) out.push_back(c);
}

int CellLocator::locate_or_nearest(const Vec2& x) const {
  int c = locate(x);
  if (c >= 0 || m_.cells.empty()) return c;
  // Rings of buckets around x until a candidate is found and no nearer one can exist.
  const int ix = bx(x.x()), iy = by(x.y());
  int best = -1;
  double best_d = INFINITY;
  const double step = std::min(cell_size_.x(), cell_size_.y());
  for (int r = 0; r <= std::max(nx_, ny_); ++r) {
    for (int j = iy - r; j <= iy + r; ++j)
      for (int i = ix - r; i <= ix + r; ++i) {
        if (i < 0 || j < 0 || i >= nx_ || j >= ny_) continue;
        if (std::max(std::abs(i - ix), std::abs(j - iy)) != r) continue;
        for (int cand : buckets_[static_cast<size_t>(j) * nx_ + i]) {
          const double d = distance(cand, x);
          if (d < best_d || (d == best_d && cand < best)) {
            best_d = d;
            best = cand;
          }
        }
      }
    if (best >= 0 && best_d <= (r - 1) * step) break;
  }
  return best;
}

}  // namespace quadapt
