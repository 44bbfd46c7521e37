#include "lpcvt/point_quality.hpp"

#include <algorithm>
#include <cmath>

#include <omp.h>

#include "lpcvt/delaunay.hpp"
#include "lpcvt/rvd.hpp"

namespace quadapt::lpcvt {

namespace {
double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}
double angle_deg(const Vec2& a, const Vec2& b) {
  double c = a.dot(b) / (a.norm() * b.norm());
  return std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / M_PI;
}
}  // namespace

AngleStats triangle_angles(const Background& bg, const Mesh& tri, bool metric) {
  AngleStats s;
  std::vector<double> largest, smallest;
  int hint = -1;
  for (int k = 0; k < tri.num_cells(); ++k) {
    const Cell& c = tri.cells[k];
    if (c.nv != 3) continue;
    Vec2 p[3];
    for (int i = 0; i < 3; ++i) p[i] = tri.nodes[c.v[i]];
    Mat2 M = Mat2::Identity();
    if (metric) {
      Vec2 z = (p[0] + p[1] + p[2]) / 3;
      int q = bg.locate(z, hint);
      if (q < 0) continue;
      hint = q;
      M = bg.metric(q, z);
    }
    double a[3];
    for (int i = 0; i < 3; ++i)
      a[i] = angle_deg(M * (p[(i + 1) % 3] - p[i]), M * (p[(i + 2) % 3] - p[i]));
    largest.push_back(std::max({a[0], a[1], a[2]}));
    smallest.push_back(std::min({a[0], a[1], a[2]}));
  }
  s.triangles = static_cast<int>(largest.size());
  if (!s.triangles) return s;
  s.median_largest = median(largest);
  s.median_smallest = median(smallest);
  int within = 0;
  for (double a : largest) {
    s.mean_largest += a / s.triangles;
    if (a >= 80 && a <= 100) ++within;
  }
  s.frac_largest_80_100 = double(within) / s.triangles;
  return s;
}

std::array<AlignmentStats, 2> voronoi_alignments(const Background& bg, const std::vector<Vec2>& sites, int from) {
  RestrictedVoronoi rvd(bg, sites);
  const int nq = bg.num_cells();
  // per cell and kind (0: metric axes, 1: principal directions): weight, weighted deviation,
  // weight within 10 degrees, edges
  std::vector<std::array<double, 8>> acc(nq);
  const int nthreads = std::max(1, omp_get_max_threads());
  std::vector<RvdWorkspace> ws(nthreads);
  std::vector<std::vector<RvdPiece>> pieces(nthreads);
#pragma omp parallel for schedule(dynamic, 16) num_threads(nthreads) if (nq >= 256 && sites.size() >= 2000)
  for (int q = 0; q < nq; ++q) {
    const int t = omp_get_thread_num();
    const int np = rvd.pieces(q, pieces[t], ws[t]);
    std::array<double, 8> a{};
    for (int k = 0; k < np; ++k) {
      const RvdPiece& pc = pieces[t][k];
      if (pc.site < from) continue;
      const int m = static_cast<int>(pc.v.size());
      for (int e = 0; e < m; ++e) {
        if (pc.label[e] < 0) continue;
        const Vec2 u = pc.v[(e + 1) % m] - pc.v[e];
        const Vec2 mid = 0.5 * (pc.v[(e + 1) % m] + pc.v[e]);
        const Mat2 M = bg.metric(pc.cell, mid);
        const Vec2 w = M * u;
        const double len = w.norm();
        if (len <= 0) continue;
        Eigen::SelfAdjointEigenSolver<Mat2> es(M.transpose() * M);
        const Vec2 wp = es.eigenvectors().transpose() * u;  // u in the eigenbasis of M^T M
        for (int kind = 0; kind < 2; ++kind) {
          const Vec2& d = kind == 0 ? w : wp;
          const double ang = std::atan2(std::abs(d.y()), std::abs(d.x())) * 180.0 / M_PI;
          const double dev = std::min(ang, 90 - ang);
          a[4 * kind] += len;
          a[4 * kind + 1] += len * dev;
          if (dev <= 10) a[4 * kind + 2] += len;
          a[4 * kind + 3] += 1;
        }
      }
    }
    acc[q] = a;
  }
  std::array<double, 8> tot{};
  for (int q = 0; q < nq; ++q)
    for (int k = 0; k < 8; ++k) tot[k] += acc[q][k];
  std::array<AlignmentStats, 2> s;
  for (int kind = 0; kind < 2; ++kind) {
    s[kind].edges = static_cast<int>(tot[4 * kind + 3]);
    if (tot[4 * kind] > 0) {
      s[kind].mean_deviation = tot[4 * kind + 1] / tot[4 * kind];
      s[kind].frac_within_10 = tot[4 * kind + 2] / tot[4 * kind];
    }
  }
  return s;
}

AlignmentStats voronoi_alignment(const Background& bg, const std::vector<Vec2>& sites, int from,
                                 bool principal) {
  return voronoi_alignments(bg, sites, from)[principal ? 1 : 0];
}

std::vector<int> valence_histogram(const std::vector<Vec2>& sites, int from) {
  DelaunayGraph dt(sites);
  std::vector<int> h;
  for (int i = from; i < dt.num_sites(); ++i) {
    int d = dt.degree(i);
    if (static_cast<int>(h.size()) <= d) h.resize(d + 1, 0);
    ++h[d];
  }
  return h;
}

nlohmann::json voronoi_json(const Background& bg, const std::vector<Vec2>& sites, int nfixed) {
  using nlohmann::json;
  json j;
  json s = json::array();
  for (const Vec2& p : sites) s.push_back({p.x(), p.y()});
  j["sites"] = s;
  j["nfixed"] = nfixed;
  json e = json::array();
  RestrictedVoronoi rvd(bg, sites);
  for (const RvdPiece& pc : rvd.all_pieces()) {
    const int m = static_cast<int>(pc.v.size());
    for (int k = 0; k < m; ++k) {
      if (pc.label[k] < 0 || pc.label[k] < pc.site) continue;
      const Vec2 &a = pc.v[k], &b = pc.v[(k + 1) % m];
      if ((a - b).norm() == 0) continue;
      e.push_back({a.x(), a.y(), b.x(), b.y()});
    }
  }
  j["edges"] = e;
  json bd = json::array();
  const Mesh& m = bg.mesh();
  for (const BoundaryEdge& be : m.boundary) {
    const Vec2 &a = m.nodes[be.v[0]], &b = m.nodes[be.v[1]];
    bd.push_back({a.x(), a.y(), b.x(), b.y()});
  }
  j["boundary"] = bd;
  return j;
}

}  // namespace quadapt::lpcvt
