#include "quad/blossom.hpp"

#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <unordered_map>

#include "core/error.hpp"
#include "gmsh/session.hpp"
#include "quad/mesh_utils.hpp"

namespace quadapt {

namespace {

struct PointKey {
  double x, y;
  bool operator<(const PointKey& o) const { return x < o.x || (x == o.x && y < o.y); }
};

}  // namespace

Mesh blossom_recombine(const Mesh& tri, const BlossomOptions& opt, BlossomStats* stats) {
  if (!tri.all_triangles()) throw InputError("mesh: Blossom recombination needs a triangulation");
  const auto loops = boundary_loops(tri);
  if (loops.empty()) throw InputError("mesh: the triangulation has no boundary");
  const double area_in = total_area(tri);

  // Order loops: the one of largest positive area is the outer loop.
  std::vector<int> order(loops.size());
  for (size_t i = 0; i < loops.size(); ++i) order[i] = static_cast<int>(i);
  std::vector<double> la(loops.size());
  for (size_t i = 0; i < loops.size(); ++i) la[i] = polygon_area(tri, loops[i]);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return la[a] > la[b]; });

  std::vector<char> on_boundary(tri.nodes.size(), 0);
  for (const auto& l : loops)
    for (int v : l) on_boundary[v] = 1;

  std::vector<std::size_t> out_node_tags;
  std::vector<double> out_coords, out_param;
  std::vector<int> etypes;
  std::vector<std::vector<std::size_t>> etags, enodes;

  {
    GmshSession session;
    gmsh_call("Blossom-Quad recombination", [&] {
      gmsh::model::add("quadapt-recombine");
      gmsh::option::setNumber("Mesh.RecombinationAlgorithm", opt.algorithm);
      gmsh::option::setNumber("Mesh.RecombineOptimizeTopology", opt.optimize_topology);
      gmsh::option::setNumber("Mesh.RecombineAll", 1);

      // Geometry: geo points = boundary nodes (tag = node + 1), geo lines = boundary edges.
      for (size_t v = 0; v < tri.nodes.size(); ++v)
        if (on_boundary[v]) gmsh::model::geo::addPoint(tri.nodes[v].x(), tri.nodes[v].y(), 0, 0, int(v) + 1);
      int line_tag = 0;
      std::vector<int> loop_tags;
      std::vector<std::array<int, 2>> line_nodes;  // per line tag - 1
      for (int li : order) {
        const auto& l = loops[li];
        std::vector<int> lines;
        for (size_t i = 0; i < l.size(); ++i) {
          int a = l[i], b = l[(i + 1) % l.size()];
          ++line_tag;
          gmsh::model::geo::addLine(a + 1, b + 1, line_tag);
          line_nodes.push_back({a, b});
          lines.push_back(line_tag);
        }
        loop_tags.push_back(gmsh::model::geo::addCurveLoop(lines));
      }
      const int surf = gmsh::model::geo::addPlaneSurface(loop_tags);
      gmsh::model::geo::synchronize();

      // Mesh: point nodes first, then line elements, then the surface's nodes and triangles.
      for (size_t v = 0; v < tri.nodes.size(); ++v)
        if (on_boundary[v])
          gmsh::model::mesh::addNodes(0, int(v) + 1, {v + 1}, {tri.nodes[v].x(), tri.nodes[v].y(), 0.0});
      for (int t = 1; t <= line_tag; ++t) {
        const auto& ln = line_nodes[t - 1];
        gmsh::model::mesh::addElementsByType(t, 1, {}, {std::size_t(ln[0]) + 1, std::size_t(ln[1]) + 1});
      }
      std::vector<std::size_t> inner_tags;
      std::vector<double> inner_xyz, inner_uv;
      for (size_t v = 0; v < tri.nodes.size(); ++v)
        if (!on_boundary[v]) {
          inner_tags.push_back(v + 1);
          inner_xyz.insert(inner_xyz.end(), {tri.nodes[v].x(), tri.nodes[v].y(), 0.0});
        }
      if (!inner_tags.empty()) {
        gmsh::model::getParametrization(2, surf, inner_xyz, inner_uv);
        if (inner_uv.size() != 2 * inner_tags.size()) inner_uv.clear();
        gmsh::model::mesh::addNodes(2, surf, inner_tags, inner_xyz, inner_uv);
      }
      std::vector<std::size_t> tri_nodes;
      tri_nodes.reserve(3 * tri.cells.size());
      for (const auto& c : tri.cells)
        for (int i = 0; i < 3; ++i) tri_nodes.push_back(std::size_t(c.v[i]) + 1);
      gmsh::model::mesh::addElementsByType(surf, 2, {}, tri_nodes);

      gmsh::model::mesh::recombine();

      gmsh::model::mesh::getNodes(out_node_tags, out_coords, out_param, -1, -1, false, false);
      gmsh::model::mesh::getElements(etypes, etags, enodes, 2, surf);
      gmsh::model::remove();
    });
  }

  // Rebuild the mesh. Boundary nodes are matched to the input by exact coordinates.
  std::map<PointKey, int> boundary_index;
  for (size_t v = 0; v < tri.nodes.size(); ++v)
    if (on_boundary[v]) boundary_index[{tri.nodes[v].x(), tri.nodes[v].y()}] = int(v);
  std::unordered_map<std::size_t, int> tag_to_pos;
  for (size_t i = 0; i < out_node_tags.size(); ++i) tag_to_pos[out_node_tags[i]] = int(i);

  Mesh out;
  out.groups = tri.groups;
  out.domain_name = tri.domain_name;
  out.domain_tag = tri.domain_tag;
  std::unordered_map<std::size_t, int> tag_to_new;
  std::vector<int> old_to_new(tri.nodes.size(), -1);
  auto node_of = [&](std::size_t tag) {
    auto it = tag_to_new.find(tag);
    if (it != tag_to_new.end()) return it->second;
    auto p = tag_to_pos.find(tag);
    if (p == tag_to_pos.end()) throw ExternalError("Gmsh recombination returned an element with an unknown node");
    Vec2 x(out_coords[3 * p->second], out_coords[3 * p->second + 1]);
    int idx = out.num_nodes();
    out.nodes.push_back(x);
    tag_to_new[tag] = idx;
    auto b = boundary_index.find({x.x(), x.y()});
    if (b != boundary_index.end()) old_to_new[b->second] = idx;
    return idx;
  };
  BlossomStats st;
  st.triangles_in = tri.num_cells();
  for (size_t k = 0; k < etypes.size(); ++k) {
    int nv = etypes[k] == 2 ? 3 : etypes[k] == 3 ? 4 : 0;
    if (nv == 0) throw ExternalError("Gmsh recombination returned an element of type " + std::to_string(etypes[k]));
    for (size_t e = 0; e < etags[k].size(); ++e) {
      Cell c;
      c.nv = nv;
      for (int i = 0; i < nv; ++i) c.v[i] = node_of(enodes[k][nv * e + i]);
      out.cells.push_back(c);
    }
  }
  st.reoriented = orient_counter_clockwise(out);
  st.quads = out.num_quads();
  st.triangles = out.num_triangles();

  // Boundary edges: the input's, mapped through the unchanged boundary nodes.
  for (const auto& e : tri.boundary) {
    int a = old_to_new[e.v[0]], b = old_to_new[e.v[1]];
    if (a < 0 || b < 0) throw ExternalError("Gmsh recombination moved or removed a boundary node");
    out.boundary.push_back({{a, b}, e.group});
  }

  // Checks: area (no overlap), boundary preserved, nothing inverted or degenerate.
  double area_abs = 0;
  for (int c = 0; c < out.num_cells(); ++c) area_abs += std::abs(cell_area(out, c));
  if (std::abs(area_abs - area_in) > 1e-9 * std::abs(area_in))
    throw ExternalError("Gmsh recombination produced overlapping or missing elements (area " +
                        std::to_string(area_abs) + " instead of " + std::to_string(area_in) + ")");
  std::vector<std::array<int, 2>> fe;
  try {
    fe = free_edges(out);
  } catch (const InputError& e) {
    throw ExternalError(std::string("Gmsh recombination produced an invalid mesh: ") + e.what());
  }
  size_t nfree_in = 0;
  for (const auto& l : loops) nfree_in += l.size();
  if (fe.size() != nfree_in)
    throw ExternalError("Gmsh recombination changed the boundary (" + std::to_string(fe.size()) + " free edges instead of " +
                        std::to_string(nfree_in) + ")");
  for (int c = 0; c < out.num_cells(); ++c) {
    const Cell& cell = out.cells[c];
    for (int i = 0; i < cell.nv; ++i) {
      Vec2 p = out.nodes[cell.v[i]];
      Vec2 en = out.nodes[cell.v[(i + 1) % cell.nv]] - p, ep = out.nodes[cell.v[(i + cell.nv - 1) % cell.nv]] - p;
      if (!(en.x() * ep.y() - en.y() * ep.x() > 0))
        throw ExternalError("Gmsh recombination produced an inverted or degenerate cell " + std::to_string(c));
    }
  }
  if (stats) *stats = st;
  return out;
}

}  // namespace quadapt
