#include "lpcvt/rvd.hpp"

namespace quadapt::lpcvt {

void clip_by_bisector(std::vector<Vec2>& v, std::vector<int>& label, const Vec2& xi,
                      const Vec2& xj, int j, std::vector<Vec2>& tmp_v, std::vector<int>& tmp_l) {
  const int m = static_cast<int>(v.size());
  const Vec2 n = xj - xi;
  const Vec2 mid = 0.5 * (xi + xj);
  double s[64];
  std::vector<double> big;
  double* sd = s;
  if (m > 64) {
    big.resize(m);
    sd = big.data();
  }
  int nin = 0;
  for (int k = 0; k < m; ++k) {
    sd[k] = n.dot(v[k] - mid);
    if (sd[k] <= 0) ++nin;
  }
  if (nin == m) return;  // untouched
  if (nin == 0) {        // entirely on x_j's side
    v.clear();
    label.clear();
    return;
  }
  tmp_v.clear();
  tmp_l.clear();
  for (int k = 0; k < m; ++k) {
    const int k1 = (k + 1 == m) ? 0 : k + 1;
    const double sa = sd[k], sb = sd[k1];
    if (sa <= 0) {
      tmp_v.push_back(v[k]);
      tmp_l.push_back(label[k]);
      if (sb > 0) {
        double t = sa / (sa - sb);
        tmp_v.push_back(v[k] + t * (v[k1] - v[k]));
        tmp_l.push_back(j);
      }
    } else if (sb <= 0) {
      double t = sa / (sa - sb);
      tmp_v.push_back(v[k] + t * (v[k1] - v[k]));
      tmp_l.push_back(label[k]);
    }
  }
  v.swap(tmp_v);
  label.swap(tmp_l);
  if (v.size() < 3) {
    v.clear();
    label.clear();
  }
}

RestrictedVoronoi::RestrictedVoronoi(const Background& bg, const std::vector<Vec2>& sites)
    : bg_(&bg), sites_(&sites), dt_(sites) {
  std::vector<Vec2> centroids(bg.num_cells());
  for (int q = 0; q < bg.num_cells(); ++q) {
    const IntegrationCell& c = bg.cell(q);
    Vec2 g = Vec2::Zero();
    for (int k = 0; k < c.nv; ++k) g += c.v[k];
    centroids[q] = g / c.nv;
  }
  start_ = dt_.nearest(centroids);
}

void RestrictedVoronoi::pieces(int q, std::vector<RvdPiece>& out, RvdWorkspace& ws) const {
  out.clear();
  const int s0 = start_[q];
  if (s0 < 0) return;
  const std::vector<Vec2>& x = *sites_;
  if (ws.stamp.size() != x.size()) ws.stamp.assign(x.size(), 0);
  const IntegrationCell& Q = bg_->cell(q);
  ws.queue.clear();
  ws.queue.push_back(s0);
  ws.stamp[s0] = q + 1;
  for (size_t head = 0; head < ws.queue.size(); ++head) {
    const int i = ws.queue[head];
    RvdPiece p;
    p.site = i;
    p.cell = q;
    p.v.assign(Q.v.begin(), Q.v.begin() + Q.nv);
    p.label.resize(Q.nv);
    for (int e = 0; e < Q.nv; ++e) p.label[e] = -1 - e;
    for (const int* j = dt_.nbr_begin(i); j != dt_.nbr_end(i) && !p.v.empty(); ++j)
      clip_by_bisector(p.v, p.label, x[i], x[*j], *j, ws.tmp_v, ws.tmp_l);
    if (p.v.empty()) continue;
    for (int l : p.label) {
      if (l >= 0 && ws.stamp[l] != q + 1) {
        ws.stamp[l] = q + 1;
        ws.queue.push_back(l);
      }
    }
    out.push_back(std::move(p));
  }
}

std::vector<RvdPiece> RestrictedVoronoi::all_pieces() const {
  std::vector<RvdPiece> all, tmp;
  RvdWorkspace ws;
  for (int q = 0; q < bg_->num_cells(); ++q) {
    pieces(q, tmp, ws);
    for (auto& p : tmp) all.push_back(std::move(p));
  }
  return all;
}

}  // namespace quadapt::lpcvt
