#include "lpcvt/delaunay.hpp"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/Spatial_sort_traits_adapter_2.h>
#include <CGAL/hilbert_sort.h>
#include <CGAL/property_map.h>

#include <algorithm>

namespace quadapt::lpcvt {

namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K>;
using Fb = CGAL::Triangulation_face_base_with_info_2<int, K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using DT = CGAL::Delaunay_triangulation_2<K, Tds>;
using Point = K::Point_2;
}  // namespace

struct DelaunayGraph::Impl {
  DT dt;
  std::vector<DT::Vertex_handle> vh;  // by site (null for hidden sites)
  std::vector<Vec2> cc;               // circumcentres by face info
};

DelaunayGraph::DelaunayGraph(DelaunayGraph&&) noexcept = default;
DelaunayGraph& DelaunayGraph::operator=(DelaunayGraph&&) noexcept = default;
DelaunayGraph::~DelaunayGraph() = default;

DelaunayGraph::DelaunayGraph(const std::vector<Vec2>& sites, bool with_triangles, bool with_voronoi)
    : impl_(std::make_unique<Impl>()), with_triangles_(with_triangles), with_voronoi_(with_voronoi) {
  build(sites);
}

void DelaunayGraph::build(const std::vector<Vec2>& sites) {
  impl_->dt.clear();
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
  if (static_cast<int>(dt.number_of_vertices()) < n) {
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
  impl_->vh.assign(n, DT::Vertex_handle());
  for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) impl_->vh[v->info()] = v;
  tables();
}

void DelaunayGraph::tables() {
  DT& dt = impl_->dt;
  const int n = static_cast<int>(hidden_.size());
  hull_ = hidden_;
  ptr_.assign(n + 1, 0);
  adj_.clear();
  vor_.clear();
  tris_.clear();
  if (dt.dimension() < 2) {
    // Collinear sites: neighbours along the line, no faces.
    std::vector<std::vector<int>> nb(n);
    for (auto e = dt.finite_edges_begin(); e != dt.finite_edges_end(); ++e) {
      int a = e->first->vertex(DT::cw(e->second))->info(), b = e->first->vertex(DT::ccw(e->second))->info();
      nb[a].push_back(b);
      nb[b].push_back(a);
    }
    for (int i = 0; i < n; ++i) {
      ptr_[i + 1] = ptr_[i] + static_cast<int>(nb[i].size());
      hull_[i] = 1;
    }
    for (auto& l : nb) adj_.insert(adj_.end(), l.begin(), l.end());
    return;
  }
  // Circumcentres of the finite faces, indexed by the face info.
  std::vector<Vec2>& cc = impl_->cc;
  cc.clear();
  if (with_voronoi_) {
    cc.reserve(dt.number_of_faces());
    for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f) {
      f->info() = static_cast<int>(cc.size());
      // from the smallest site index on, so that the rounding does not depend on which
      // rotation of the triangle the face record holds (that depends on the flip history)
      int r = 0;
      for (int k = 1; k < 3; ++k)
        if (f->vertex(k)->info() < f->vertex(r)->info()) r = k;
      Point c = CGAL::circumcenter(f->vertex(r)->point(), f->vertex(DT::ccw(r))->point(),
                                   f->vertex(DT::cw(r))->point());
      cc.emplace_back(c.x(), c.y());
    }
  }
  // Adjacency from the faces around each vertex, counter-clockwise: face k = (v, n_k, n_k+1),
  // starting at the face whose n_k is the smallest neighbour (canonical: independent of how the
  // triangulation was made).
  std::vector<DT::Face_handle> first(n);
  for (int i = 0; i < n; ++i) {
    DT::Vertex_handle v = impl_->vh[i];
    if (v == DT::Vertex_handle()) continue;
    auto f = dt.incident_faces(v), done = f;
    int d = 0, best = -1;
    if (f != nullptr) do {
        const int iv = f->index(v);
        auto a = f->vertex(DT::ccw(iv));
        if (!dt.is_infinite(a)) {
          ++d;
          if (best < 0 || a->info() < best) {
            best = a->info();
            first[i] = f;
          }
        }
        if (dt.is_infinite(f)) hull_[i] = 1;
      } while (++f != done);
    ptr_[i + 1] = d;
  }
  for (int i = 0; i < n; ++i) ptr_[i + 1] += ptr_[i];
  adj_.resize(ptr_[n]);
  if (with_voronoi_) vor_.assign(ptr_[n], Vec2::Zero());
  if (with_triangles_) tris_.reserve(dt.number_of_faces());
  for (int i = 0; i < n; ++i) {
    DT::Vertex_handle v = impl_->vh[i];
    if (v == DT::Vertex_handle() || ptr_[i + 1] == ptr_[i]) continue;
    auto f = dt.incident_faces(v, first[i]), done = f;
    int k = ptr_[i];
    const size_t first_tri = tris_.size();
    do {
      const int iv = f->index(v);
      auto a = f->vertex(DT::ccw(iv));
      if (!dt.is_infinite(a)) {
        if (with_voronoi_ && !hull_[i]) vor_[k] = cc[f->info()];
        adj_[k++] = a->info();
      }
      // the triangles sorted by (smallest vertex, the vertices as CGAL's face holds them):
      // gathered at their smallest vertex, each group sorted (a few faces; no global sort)
      if (with_triangles_ && !dt.is_infinite(f)) {
        const std::array<int, 3> t = {f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()};
        if (std::min({t[0], t[1], t[2]}) == i) tris_.push_back(t);
      }
    } while (++f != done);
    std::sort(tris_.begin() + first_tri, tris_.end());
  }
}

bool DelaunayGraph::update(const std::vector<Vec2>& sites, int* flips) {
  if (flips) *flips = 0;
  DT& dt = impl_->dt;
  const int n = static_cast<int>(hidden_.size());
  const bool ok = static_cast<int>(sites.size()) == n && dt.dimension() == 2 &&
                  static_cast<int>(dt.number_of_vertices()) == n;
  if (!ok) {
    build(sites);
    return false;
  }
  // Sites on the convex hull that move, and the vertices of triangles the move would invert,
  // stay at their old positions (the set grows until no triangle is inverted): the
  // triangulation stays valid with the same hull, the flips make it Delaunay, and these sites
  // are moved afterwards one by one (CGAL's move keeps the triangulation Delaunay).
  std::vector<Point> old(n);
  std::vector<char> deferred(n, 0);
  std::vector<int> later;
  for (int i = 0; i < n; ++i) {
    old[i] = impl_->vh[i]->point();
    const Point p(sites[i].x(), sites[i].y());
    if (hull_[i] && p != old[i]) {
      deferred[i] = 1;
      later.push_back(i);
    } else {
      impl_->vh[i]->set_point(p);
    }
  }
  for (int round = 0;; ++round) {
    bool inverted = false;
    for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f)
      if (CGAL::orientation(f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point()) != CGAL::LEFT_TURN) {
        inverted = true;
        for (int k = 0; k < 3; ++k) {
          const int i = f->vertex(k)->info();
          if (!deferred[i]) {
            deferred[i] = 1;
            later.push_back(i);
            impl_->vh[i]->set_point(old[i]);
          }
        }
      }
    if (!inverted) break;
    if (round > 20 || static_cast<int>(later.size()) > n / 20 + 10) {
      build(sites);
      return false;
    }
  }
  // Lawson flips until every interior edge is (symbolically perturbed) Delaunay.
  std::vector<std::pair<DT::Face_handle, int>> stack;
  for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f)
    for (int i = 0; i < 3; ++i) {
      DT::Face_handle g = f->neighbor(i);
      // each interior edge once, from the face that sees it as (smaller, larger) site index
      // (not by comparing face addresses, which differ from run to run)
      if (!dt.is_infinite(g) && f->vertex(DT::ccw(i))->info() < f->vertex(DT::cw(i))->info())
        stack.emplace_back(f, i);
    }
  int nflip = 0;
  while (!stack.empty()) {
    auto [f, i] = stack.back();
    stack.pop_back();
    DT::Face_handle g = f->neighbor(i);
    if (dt.is_infinite(f) || dt.is_infinite(g)) continue;
    if (dt.side_of_oriented_circle(g, f->vertex(i)->point(), true) != CGAL::ON_POSITIVE_SIDE) continue;
    dt.flip(f, i);
    ++nflip;
    for (int k = 0; k < 3; ++k) {
      stack.emplace_back(f, k);
      stack.emplace_back(g, k);
    }
    if (nflip > 4 * n + 1000) {  // cannot happen for a valid start; be safe
      build(sites);
      return false;
    }
  }
  std::sort(later.begin(), later.end());
  for (int i : later) {
    const Point p(sites[i].x(), sites[i].y());
    // (in dimension 2 CGAL keeps the vertex handle; another handle means a collision)
    if (dt.move_if_no_collision(impl_->vh[i], p) != impl_->vh[i]) {
      build(sites);
      return false;
    }
  }
  if (flips) *flips = nflip;
  tables();
  return true;
}

std::vector<std::array<int, 2>> DelaunayGraph::edges() const {
  std::vector<std::array<int, 2>> e;
  e.reserve(adj_.size() / 2);
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

std::vector<int> spatial_order(const std::vector<Vec2>& sites, int from) {
  const int n = static_cast<int>(sites.size());
  from = std::max(0, from);
  std::vector<Point> pts;
  pts.reserve(n);
  for (const Vec2& p : sites) pts.emplace_back(p.x(), p.y());
  std::vector<std::size_t> idx;
  for (int i = from; i < n; ++i) idx.push_back(i);
  using Traits = CGAL::Spatial_sort_traits_adapter_2<K, CGAL::Pointer_property_map<Point>::type>;
  // The median policy splits by rank (std::nth_element): deterministic for a given input.
  CGAL::hilbert_sort(idx.begin(), idx.end(), Traits(CGAL::make_property_map(pts)),
                     CGAL::Hilbert_sort_median_policy());
  return std::vector<int>(idx.begin(), idx.end());
}

}  // namespace quadapt::lpcvt
