#include "lpcvt/rvd.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#include "core/error.hpp"

namespace quadapt::lpcvt {

namespace {

/// Clips the polygon (v, label) by the half-plane n . y <= d; the new edge gets `lab`.
/// Returns false when nothing is left.
bool clip_halfplane(std::vector<Vec2>& v, std::vector<int>& label, const Vec2& n, double d, int lab,
                    std::vector<Vec2>& tmp_v, std::vector<int>& tmp_l) {
  const int m = static_cast<int>(v.size());
  double s[64];
  std::vector<double> big;
  double* sd = s;
  if (m > 64) {
    big.resize(m);
    sd = big.data();
  }
  int nin = 0;
  for (int k = 0; k < m; ++k) {
    sd[k] = n.dot(v[k]) - d;
    if (sd[k] <= 0) ++nin;
  }
  if (nin == m) return true;
  if (nin == 0) {
    v.clear();
    label.clear();
    return false;
  }
  // into a buffer on the stack (two vertices per edge at most), then copied back: no
  // per-vertex capacity checks, and v keeps its storage (the same arithmetic as before)
  constexpr int kStack = 64;
  Vec2 buf_v[kStack];
  int buf_l[kStack];
  Vec2* ov = buf_v;
  int* ol = buf_l;
  if (2 * m > kStack) {
    tmp_v.resize(2 * m);
    tmp_l.resize(2 * m);
    ov = tmp_v.data();
    ol = tmp_l.data();
  }
  int c = 0;
  for (int k = 0; k < m; ++k) {
    const int k1 = (k + 1 == m) ? 0 : k + 1;
    const double sa = sd[k], sb = sd[k1];
    if (sa <= 0) {
      ov[c] = v[k];
      ol[c++] = label[k];
      if (sb > 0) {
        double t = sa / (sa - sb);
        ov[c] = v[k] + t * (v[k1] - v[k]);
        ol[c++] = lab;
      }
    } else if (sb <= 0) {
      double t = sa / (sa - sb);
      ov[c] = v[k] + t * (v[k1] - v[k]);
      ol[c++] = label[k];
    }
  }
  v.assign(ov, ov + c);
  label.assign(ol, ol + c);
  if (v.size() < 3) {
    v.clear();
    label.clear();
    return false;
  }
  return true;
}

}  // namespace

void clip_by_bisector(std::vector<Vec2>& v, std::vector<int>& label, const Vec2& xi,
                      const Vec2& xj, int j, std::vector<Vec2>& tmp_v, std::vector<int>& tmp_l) {
  const Vec2 n = xj - xi;
  clip_halfplane(v, label, n, n.dot(0.5 * (xi + xj)), j, tmp_v, tmp_l);
}

void clip_by_bisector(std::vector<Vec2>& v, std::vector<int>& label, const Vec2& xi,
                      const Vec2& xj, const Mat2& G, int j, std::vector<Vec2>& tmp_v,
                      std::vector<int>& tmp_l) {
  const Vec2 n = G * (xj - xi);
  clip_halfplane(v, label, n, n.dot(0.5 * (xi + xj)), j, tmp_v, tmp_l);
}

namespace {
std::atomic<long> next_rvd_id{1};
}  // namespace

namespace {
/// The flip rule's metric: the background cell's at the flip quadrilateral's centroid (walks
/// from the previous answer).
struct QuadMetric {
  const Background& bg;
  int hint = -1;
  Mat2 operator()(const std::array<Vec2, 4>& q) {
    int c = bg.locate_near(0.25 * (q[0] + q[1] + q[2] + q[3]), hint);
    if (c < 0) return Mat2::Zero();  // a chord outside the domain: never flipped
    hint = c;
    return bg.cell(c).M;
  }
};
/// Independent QuadMetric objects (own hints) for the parallel first tests of the flips.
EdgeMetricFactory quad_metrics(const Background& bg) {
  return [&bg]() -> EdgeMetric { return QuadMetric{bg}; };
}
}  // namespace

MetricGraph build_metric_graph(const Background& bg, const std::vector<Vec2>& sites,
                               std::vector<std::array<int, 3>> tris) {
  QuadMetric m{bg};
  return metric_delaunay(sites, std::move(tris), [&](const std::array<Vec2, 4>& q) { return m(q); },
                         quad_metrics(bg));
}

bool update_metric_graph(const Background& bg, const std::vector<Vec2>& sites, MetricGraph& g, int max_inverted) {
  QuadMetric m{bg};
  return metric_delaunay_update(sites, g, [&](const std::array<Vec2, 4>& q) { return m(q); }, max_inverted,
                                quad_metrics(bg));
}

MetricGraph build_metric_graph(const Background& bg, const std::vector<Vec2>& sites,
                               const DelaunayGraph& dt) {
  return build_metric_graph(bg, sites, dt.triangles());
}

RestrictedVoronoi::RestrictedVoronoi(const Background& bg, const std::vector<Vec2>& sites)
    : bg_(&bg), sites_(&sites), id_(next_rvd_id++),
      own_(std::make_unique<DelaunayGraph>(sites, bg.metric_cells(), !bg.metric_cells())) {
  dt_ = own_.get();
  if (bg.metric_cells()) {
    own_mg_ = std::make_unique<MetricGraph>(build_metric_graph(bg, sites, *dt_));
    mg_ = own_mg_.get();
  }
  find_starts();
}

RestrictedVoronoi::RestrictedVoronoi(const Background& bg, const std::vector<Vec2>& sites, const DelaunayGraph& dt)
    : bg_(&bg), sites_(&sites), id_(next_rvd_id++), dt_(&dt) {
  if (bg.metric_cells()) {
    own_mg_ = std::make_unique<MetricGraph>(build_metric_graph(bg, sites, dt));
    mg_ = own_mg_.get();
  }
  find_starts();
}

RestrictedVoronoi::RestrictedVoronoi(const Background& bg, const std::vector<Vec2>& sites, const DelaunayGraph& dt,
                                     const MetricGraph* mg)
    : bg_(&bg), sites_(&sites), id_(next_rvd_id++), dt_(&dt), mg_(mg) {
  find_starts();
}

RestrictedVoronoi::RestrictedVoronoi(const Background& bg, const std::vector<Vec2>& sites, const MetricGraph& mg,
                                     std::vector<int> start_guess, const SiteTree* tree)
    : bg_(&bg), sites_(&sites), id_(next_rvd_id++), mg_(&mg), tree_(tree), start_(std::move(start_guess)) {
  if (static_cast<int>(start_.size()) != bg.num_cells())
    throw NumericalError("RestrictedVoronoi: one start guess per integration cell expected");
  if (tree && tree->size() != static_cast<int>(sites.size()))
    throw NumericalError("RestrictedVoronoi: the site tree is not of these sites");
  find_starts();
}

void RestrictedVoronoi::find_starts() {
  const Background& bg = *bg_;
  std::vector<Vec2> centroids(bg.num_cells());
  for (int q = 0; q < bg.num_cells(); ++q) {
    const IntegrationCell& c = bg.cell(q);
    Vec2 g = Vec2::Zero();
    for (int k = 0; k < c.nv; ++k) g += c.v[k];
    centroids[q] = g / c.nv;
  }
  if (dt_) start_ = dt_->nearest(centroids);  // else the guesses given
  if (!mg_) return;
  if (!tree_) {
    own_tree_ = std::make_unique<SiteTree>(*sites_);
    tree_ = own_tree_.get();
  }
  // nearest in G_Q: greedy walk over the metric graph from the Euclidean nearest site (exact for
  // a Delaunay graph of the mapped sites; the centroid then lies in the start site's cell)
  const std::vector<Vec2>& x = *sites_;
  // each cell on its own (any thread, same answers); parallel where there is enough work
  const int nq = bg.num_cells();
#pragma omp parallel if (nq >= 256 && x.size() >= 2000)
  {
    std::vector<int> cand;  // the exact check's sites, reused (one allocation per thread, not per cell)
#pragma omp for schedule(static)
    for (int q = 0; q < nq; ++q) {
      int s = start_[q];
      if (s < 0) continue;
      const Mat2 G = bg.partition_metric(q);
      auto dist = [&](int i) {
        const Vec2 d = x[i] - centroids[q];
        return d.dot(G * d);
      };
      double ds = dist(s);
      // greedy descent over the neighbours (the graph is Delaunay for the midpoint metrics, which
      // may differ from G_Q where the frame grades): it only shrinks the exact check's box below,
      // whose answer — the nearest site, the lowest index among equals — does not depend on it
      // (but for sites on the box's edge to rounding; every output compared was the same bytes)
      // (checking the neighbours' neighbours too cost more than the smaller box saved: 3 % of a loop
      // step's instructions)
      for (int guard = 0; guard < 10000; ++guard) {
        int best = -1;
        for (const int* j = mg_->nbr_begin(s); j != mg_->nbr_end(s); ++j)
          if (dist(*j) < ds) {
            ds = dist(*j);
            best = *j;
          }
        if (best < 0) break;
        s = best;
      }
      // exact: every site in the box of the G-ellipse through s
      {
        const Mat2 Gi = G.inverse();
        const Vec2 ext(std::sqrt(ds * Gi(0, 0)), std::sqrt(ds * Gi(1, 1)));
        cand.clear();
        tree_->query(centroids[q] - ext, centroids[q] + ext, cand);
        for (int j : cand)
          if (dist(j) < ds || (dist(j) == ds && j < s)) {
            ds = dist(j);
            s = j;
          }
      }
      start_[q] = s;
    }
  }
}


RestrictedVoronoi::Candidates RestrictedVoronoi::security_candidates(int i, const Vec2& ext, RvdWorkspace& ws) const {
  const std::vector<Vec2>& x = *sites_;
  if (ws.box_owner != id_ || ws.box_gen.size() != x.size()) {
    if (ws.box_gen.size() != x.size() || ws.box_epoch == std::numeric_limits<int>::max()) {
      ws.box_gen.assign(x.size(), 0);
      ws.box_ext.resize(x.size());
      ws.box_at.resize(x.size());
      ws.box_epoch = 0;
    }
    ++ws.box_epoch;
    ws.box_owner = id_;
    ws.box_sites.clear();
    ws.box_d.clear();
  }
  if (ws.box_gen[i] == ws.box_epoch && ext.x() <= ws.box_ext[i].x() && ext.y() <= ws.box_ext[i].y()) {
    ++ws.box_hits;
    const int at = ws.box_at[i][0];
    return {ws.box_sites.data() + at, ws.box_d.data() + at, ws.box_at[i][1]};
  }
  ++ws.box_queries;
  const Vec2 e = kBoxMargin * ext;
  const int at = static_cast<int>(ws.box_sites.size());
  tree_->query(x[i] - e, x[i] + e, ws.box_sites);
  const int n = static_cast<int>(ws.box_sites.size()) - at;
  ws.box_d.resize(ws.box_sites.size());
  for (int k = at; k < at + n; ++k) ws.box_d[k] = x[ws.box_sites[k]] - x[i];
  ws.box_gen[i] = ws.box_epoch;
  ws.box_ext[i] = e;
  ws.box_at[i] = {at, n};
  return {ws.box_sites.data() + at, ws.box_d.data() + at, n};
}

int RestrictedVoronoi::pieces(int q, std::vector<RvdPiece>& out, RvdWorkspace& ws) const {
  const int s0 = start_[q];
  if (s0 < 0) return 0;
  const std::vector<Vec2>& x = *sites_;
  if (ws.stamp.size() != x.size() || ws.gen == std::numeric_limits<int>::max()) {
    ws.stamp.assign(x.size(), 0);
    ws.gen = 0;
  }
  const int gen = ++ws.gen;
  const IntegrationCell& Q = bg_->cell(q);
  // Q's edges as half-planes n_e . y <= d_e (inside on the left of the CCW edges)
  Vec2 qn[4];
  double qd[4];
  for (int e = 0; e < Q.nv; ++e) {
    const Vec2 t = Q.v[(e + 1) % Q.nv] - Q.v[e];
    qn[e] = Vec2(t.y(), -t.x());
    qd[e] = qn[e].dot(Q.v[e]);
  }
  const bool poly = !mg_ && dt_->has_voronoi();
  const Mat2 G = bg_->partition_metric(q);
  // how many times the sites of the ellipse {d : d^T G d < r^2} its axis-aligned box holds,
  // over the same for an ellipse along the axes: 1 along the axes, ~5 for 10:1 at 45 degrees,
  // ~43 for 100:1 at 30 (the grid's threshold and the ellipse query below both use it)
  const double box_excess = std::sqrt(G(0, 0) * G(1, 1) / G.determinant());
  ws.queue.clear();
  ws.queue.push_back(s0);
  ws.stamp[s0] = gen;
  int count = 0;
  int grid = mg_ && grid_min_sites_ > 0 ? 0 : -1;  // the cell's grid: 0 not decided, 1 built, -1 none
  for (size_t head = 0; head < ws.queue.size(); ++head) {
    const int i = ws.queue[head];
    if (static_cast<int>(out.size()) <= count) out.emplace_back();
    RvdPiece& p = out[count];
    p.site = i;
    p.cell = q;
    const int deg = mg_ ? 0 : dt_->degree(i);
    if (mg_) {
      // Q clipped by the G_Q-bisectors of the metric neighbours, then of every site within the
      // security radius: the piece is exact when each site j with |x_j - x_i|_G < 2 R (R the
      // largest G-distance from x_i to a vertex of the piece) has clipped it. The graph is the
      // metric Delaunay graph for the metric at each edge's midpoint, which may differ from
      // G_Q where the frame grades (and a walk over it may miss sites): the search uses the
      // site tree, so the energy has no jumps when the graph flips.
      p.v.assign(Q.v.begin(), Q.v.begin() + Q.nv);
      p.label.resize(Q.nv);
      for (int e = 0; e < Q.nv; ++e) p.label[e] = -1 - e;
      if (ws.seen.size() != x.size() || ws.seen_gen == std::numeric_limits<int>::max()) {
        ws.seen.assign(x.size(), 0);
        ws.seen_gen = 0;
      }
      const int sg = ++ws.seen_gen;
      ws.seen[i] = sg;
      for (const int* j = mg_->nbr_begin(i); j != mg_->nbr_end(i); ++j) {
        ws.seen[*j] = sg;
        if (!p.v.empty()) clip_by_bisector(p.v, p.label, x[i], x[*j], G, *j, ws.tmp_v, ws.tmp_l);
      }
      // every site within 2R (|d|_G < 2R: from the cell's bucket grid, or the box of that
      // G-ellipse from the site tree); R only shrinks as the piece is clipped, so one pass with
      // the first R suffices
      if (!p.v.empty()) {
        double R2 = 0;
        for (const Vec2& v : p.v) R2 = std::max(R2, (v - x[i]).dot(G * (v - x[i])));
        if (grid == 0) {
          // decided at the cell's first search, from its size in units of that piece (a site's
          // cell has metric area ~2 R^2): a grid the size of the spacing over Q widened by 4R,
          // which covers the disks of pieces up to 2x that R whose site is in Q and 1.33x for
          // sites outside Q; candidates() checks, and a disk it does not cover asks the tree
          grid = -1;
          // The site tree answers a search with the ellipse's axis-aligned box (box_excess
          // above): the grid pays from grid_min_sites *box* sites on (measured,
          // docs/bench-lpcvt-history.md, "The ratios at a395b21": 100:1 at 30 degrees on 16 x 16
          // cells, ~12 sites a cell, 0.55x the CPU, the same output)
          if (Q.area * std::sqrt(G.determinant()) * box_excess >= grid_min_sites_ * 2 * R2 &&
              ws.grid.build(G, Q.v.data(), Q.nv, 4 * std::sqrt(R2), std::sqrt(2 * R2), *tree_, x, 1 << 20)) {
            grid = 1;
            ++ws.grid_builds;
          }
        }
        ws.ring.clear();
        ws.cand.clear();
        auto keep = [&](int j) {
          if (ws.seen[j] == sg) return;
          const Vec2 d = x[j] - x[i];
          if (d.dot(G * d) < 4 * R2) ws.ring.push_back(j);
        };
        if (grid == 1 && ws.grid.candidates(x[i], 2 * std::sqrt(R2), ws.cand)) {
          ++ws.grid_searches;
          for (int j : ws.cand) keep(j);
        } else {
          const Mat2 Gi = G.inverse();
          // the ellipse's axis-aligned box over its area: 4/pi for a circle, ~0.6 x the axis
          // ratio for a thin oblique ellipse (the box of a 500:1 ellipse at 30 degrees held
          // ~2,300 sites per search, to keep ~3)
          if ((4 / M_PI) * box_excess > ellipse_ratio_) {
            ++ws.ellipse_queries;
            ws.cand.clear();
            tree_->query_ellipse(x[i], G, 4 * R2, ws.cand);
            for (int j : ws.cand) keep(j);
          } else {
            const Vec2 ext(2 * std::sqrt(R2 * Gi(0, 0)), 2 * std::sqrt(R2 * Gi(1, 1)));
            // keep()'s tests in the other order: the distance from the cached offsets first
            // (read in order), the site's own memory only for the few within 2R (the same sites)
            const Candidates box = security_candidates(i, ext, ws);
            for (int t = 0; t < box.n; ++t) {
              const Vec2& d = box.d[t];
              if (d.dot(G * d) < 4 * R2 && ws.seen[box.site[t]] != sg) ws.ring.push_back(box.site[t]);
            }
          }
        }
        // the same sites whichever search found them (cell_grid.hpp), clipped in one fixed
        // order: the same piece
        std::sort(ws.ring.begin(), ws.ring.end());
        for (int j : ws.ring) {
          clip_by_bisector(p.v, p.label, x[i], x[j], G, j, ws.tmp_v, ws.tmp_l);
          if (p.v.empty()) break;
        }
      }
    } else if (poly && !dt_->on_hull(i) && deg >= 3) {
      // the Voronoi polygon, clipped by Q
      const Vec2* c = dt_->vor_begin(i);
      const int* nb = dt_->nbr_begin(i);
      p.v.assign(c, c + deg);
      p.label.resize(deg);
      for (int k = 0; k < deg; ++k) p.label[k] = nb[k + 1 == deg ? 0 : k + 1];
      for (int e = 0; e < Q.nv; ++e)
        if (!clip_halfplane(p.v, p.label, qn[e], qd[e], -1 - e, ws.tmp_v, ws.tmp_l)) break;
    } else {
      p.v.assign(Q.v.begin(), Q.v.begin() + Q.nv);
      p.label.resize(Q.nv);
      for (int e = 0; e < Q.nv; ++e) p.label[e] = -1 - e;
      for (const int* j = dt_->nbr_begin(i); j != dt_->nbr_end(i) && !p.v.empty(); ++j)
        clip_by_bisector(p.v, p.label, x[i], x[*j], *j, ws.tmp_v, ws.tmp_l);
    }
    if (p.v.empty()) continue;
    for (int l : p.label) {
      if (l >= 0 && ws.stamp[l] != gen) {
        ws.stamp[l] = gen;
        ws.queue.push_back(l);
      }
    }
    ++count;
  }
  return count;
}

std::vector<RvdPiece> RestrictedVoronoi::all_pieces(RvdWorkspace* w) const {
  std::vector<RvdPiece> all, tmp;
  RvdWorkspace local;
  RvdWorkspace& ws = w ? *w : local;
  for (int q = 0; q < bg_->num_cells(); ++q) {
    const int n = pieces(q, tmp, ws);
    for (int k = 0; k < n; ++k) all.push_back(tmp[k]);
  }
  return all;
}

}  // namespace quadapt::lpcvt
