#include "lpcvt/delaunay.hpp"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>

namespace quadapt::lpcvt {

namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb>;
using DT = CGAL::Delaunay_triangulation_2<K, Tds>;
using Point = K::Point_2;
}  // namespace

struct DelaunayGraph::Impl {
  DT dt;
};

DelaunayGraph::DelaunayGraph(DelaunayGraph&&) noexcept = default;
DelaunayGraph& DelaunayGraph::operator=(DelaunayGraph&&) noexcept = default;
DelaunayGraph::~DelaunayGraph() = default;

DelaunayGraph::DelaunayGraph(const std::vector<Vec2>& sites) : impl_(std::make_unique<Impl>()) {
  const int n = static_cast<int>(sites.size());
  std::vector<std::pair<Point, int>> pts;
  pts.reserve(n);
  for (int i = 0; i < n; ++i) pts.emplace_back(Point(sites[i].x(), sites[i].y()), i);
  DT& dt = impl_->dt;
  // Range insertion (spatially sorted). For duplicates CGAL keeps one vertex; make the info
  // deterministic (the smallest index) by a second pass.
  dt.insert(pts.begin(), pts.end());
  hidden_.assign(n, 1);
  for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) hidden_[v->info()] = 0;
  {
    // A hidden site may be the smaller index of a duplicate pair: give the vertex the smallest.
    std::vector<int> order;
    for (int i = 0; i < n; ++i)
      if (hidden_[i]) order.push_back(i);
    for (int i : order) {
      auto vh = dt.nearest_vertex(pts[i].first);
      if (vh != nullptr && vh->point() == pts[i].first && i < vh->info()) {
        hidden_[vh->info()] = 1;
        vh->info() = i;
        hidden_[i] = 0;
      }
    }
  }
  ptr_.assign(n + 1, 0);
  std::vector<std::vector<int>> nb(n);
  for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) {
    auto c = dt.incident_vertices(v), done = c;
    if (c == nullptr) continue;
    do {
      if (!dt.is_infinite(c)) nb[v->info()].push_back(c->info());
    } while (++c != done);
  }
  for (int i = 0; i < n; ++i) ptr_[i + 1] = ptr_[i] + static_cast<int>(nb[i].size());
  adj_.reserve(ptr_[n]);
  for (auto& l : nb) adj_.insert(adj_.end(), l.begin(), l.end());
  if (dt.dimension() == 2) {
    for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f)
      tris_.push_back({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
    std::sort(tris_.begin(), tris_.end(), [](const auto& a, const auto& b) {
      auto ka = std::min({a[0], a[1], a[2]}), kb = std::min({b[0], b[1], b[2]});
      return ka != kb ? ka < kb : a < b;
    });
  }
}

std::vector<std::array<int, 2>> DelaunayGraph::edges() const {
  std::vector<std::array<int, 2>> e;
  for (int i = 0; i < num_sites(); ++i)
    for (const int* j = nbr_begin(i); j != nbr_end(i); ++j)
      if (i < *j) e.push_back({i, *j});
  std::sort(e.begin(), e.end());
  return e;
}

std::vector<int> DelaunayGraph::nearest(const std::vector<Vec2>& queries) const {
  std::vector<int> out(queries.size(), -1);
  const DT& dt = impl_->dt;
  if (dt.number_of_vertices() == 0) return out;
  DT::Vertex_handle hint = dt.finite_vertices_begin();
  for (size_t k = 0; k < queries.size(); ++k) {
    DT::Face_handle f = hint->face();
    auto v = dt.nearest_vertex(Point(queries[k].x(), queries[k].y()), f);
    out[k] = v->info();
    hint = v;
  }
  return out;
}

}  // namespace quadapt::lpcvt
