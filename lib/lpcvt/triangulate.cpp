#include "lpcvt/triangulate.hpp"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <list>
#include <map>
#include <sstream>

#include "core/error.hpp"
#include "core/format.hpp"
#include "mesh/mesh.hpp"

namespace quadapt::lpcvt {

namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K>;
using Fbi = CGAL::Triangulation_face_base_with_info_2<int, K>;
using Fb = CGAL::Constrained_triangulation_face_base_2<K, Fbi>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using Itag = CGAL::No_constraint_intersection_requiring_constructions_tag;
using CDT = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, Itag>;
using Point = K::Point_2;

/// Nesting depth of every face: 0 outside, +1 across each constraint (CGAL's mark_domains).
void mark_domains(CDT& cdt) {
  for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f) f->info() = -1;
  std::list<CDT::Edge> border;
  auto flood = [&](CDT::Face_handle start, int index) {
    std::list<CDT::Face_handle> queue;
    queue.push_back(start);
    while (!queue.empty()) {
      CDT::Face_handle fh = queue.front();
      queue.pop_front();
      if (fh->info() != -1) continue;
      fh->info() = index;
      for (int i = 0; i < 3; ++i) {
        CDT::Edge e(fh, i);
        CDT::Face_handle n = fh->neighbor(i);
        if (n->info() == -1) {
          if (cdt.is_constrained(e))
            border.push_back(e);
          else
            queue.push_back(n);
        }
      }
    }
  };
  flood(cdt.infinite_face(), 0);
  while (!border.empty()) {
    CDT::Edge e = border.front();
    border.pop_front();
    CDT::Face_handle n = e.first->neighbor(e.second);
    if (n->info() == -1) flood(n, e.first->info() + 1);
  }
}

}  // namespace

Mesh triangulate_domain(const std::vector<Vec2>& sites_in, int nfixed,
                        const std::vector<std::array<int, 2>>& segments,
                        const std::vector<int>& segment_group, const Mesh& background) {
  std::vector<Vec2> sites = sites_in;
  std::vector<char> drop(sites.size(), 0);
  for (int attempt = 0; attempt < 3; ++attempt) {
    CDT cdt;
    std::vector<std::pair<Point, int>> pts;
    for (int i = 0; i < static_cast<int>(sites.size()); ++i)
      if (!drop[i]) pts.emplace_back(Point(sites[i].x(), sites[i].y()), i);
    cdt.insert(pts.begin(), pts.end());
    std::vector<CDT::Vertex_handle> vh(sites.size());
    for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v) vh[v->info()] = v;
    for (auto s : segments) {
      if (vh[s[0]] == CDT::Vertex_handle() || vh[s[1]] == CDT::Vertex_handle()) {
        const Vec2& x = sites[vh[s[0]] == CDT::Vertex_handle() ? s[0] : s[1]];
        throw NumericalError("two boundary points coincide at " + sci_point(x.x(), x.y()) +
                             ": the domain's boundary passes twice there (a duplicated boundary edge, or walls that touch)");
      }
      try {
        cdt.insert_constraint(vh[s[0]], vh[s[1]]);
      } catch (const std::exception&) {
        throw NumericalError("boundary segments intersect each other near " +
                             sci_point(sites[s[0]].x(), sites[s[0]].y()) + ": the domain's boundary crosses itself");
      }
    }
    // A free site on a segment splits the constraint: drop such sites and start again.
    bool split = false;
    for (auto s : segments) {
      if (cdt.is_edge(vh[s[0]], vh[s[1]])) continue;
      const Vec2 &a = sites[s[0]], &b = sites[s[1]];
      for (int i = nfixed; i < static_cast<int>(sites.size()); ++i)
        if (!drop[i] && segment_distance(sites[i], a, b) <= 1e-9 * (b - a).norm()) {
          drop[i] = 1;
          split = true;
        }
    }
    if (split) continue;
    mark_domains(cdt);
    Mesh m;
    m.groups = background.groups;
    m.domain_name = background.domain_name;
    m.domain_tag = background.domain_tag;
    std::vector<int> node_of(sites.size(), -1);
    auto node = [&](int s) {
      if (node_of[s] < 0) {
        node_of[s] = m.num_nodes();
        m.nodes.push_back(sites[s]);
      }
      return node_of[s];
    };
    // deterministic order: faces sorted by their (sorted) site triples
    std::vector<std::array<int, 3>> tris;
    for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f)
      if (f->info() % 2 == 1) tris.push_back({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
    for (auto& t : tris) std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    std::sort(tris.begin(), tris.end());
    std::map<std::pair<int, int>, int> directed;  // site edge a->b of an inside triangle
    for (auto& t : tris) {
      Cell c;
      c.nv = 3;
      for (int k = 0; k < 3; ++k) {
        c.v[k] = node(t[k]);
        directed[{t[k], t[(k + 1) % 3]}] = 1;
      }
      m.cells.push_back(c);
    }
    for (size_t k = 0; k < segments.size(); ++k) {
      int a = segments[k][0], b = segments[k][1];
      if (!directed.count({a, b}) && directed.count({b, a})) std::swap(a, b);
      BoundaryEdge be;
      be.v = {node(a), node(b)};
      be.group = segment_group[k];
      m.boundary.push_back(be);
    }
    return m;
  }
  throw NumericalError("could not conform the triangulation to the boundary");
}

}  // namespace quadapt::lpcvt
