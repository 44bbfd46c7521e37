#include "gmsh/gmsh_recombine.hpp"

#include <gmsh.h>

#include <array>
#include <cstdint>
#include <string>
#include <unordered_map>

#include "core/error.hpp"
#include "gmsh/plugin.hpp"
#include "gmsh/session.hpp"

namespace quadapt {

GmshRecombined gmsh_plugin::sdk_gmsh_recombine(const Mesh& tri, const std::vector<std::vector<int>>& loops,
                                              const std::vector<char>& on_boundary,
                                              const GmshRecombineOptions& opt) {
  std::vector<std::size_t> node_tags;
  std::vector<double> coords, param;
  std::vector<int> etypes;
  std::vector<std::vector<std::size_t>> etags, enodes;
  GmshSession session;
  const GmshModelScope model("quadapt-recombine");  // removed however the call ends
  gmsh_call("Blossom-Quad recombination", [&] {
    gmsh::model::add(model.name());
    const GmshOptionGuard options({{"Mesh.RecombinationAlgorithm", opt.algorithm},
                                   {"Mesh.RecombineOptimizeTopology", opt.optimize_topology},
                                   {"Mesh.Smoothing", opt.smoothing},
                                   {"Mesh.RecombineAll", 1}});

    // Geometry: geo points = boundary nodes (tag = node + 1), geo lines = boundary edges.
    for (size_t v = 0; v < tri.nodes.size(); ++v)
      if (on_boundary[v]) gmsh::model::geo::addPoint(tri.nodes[v].x(), tri.nodes[v].y(), 0, 0, int(v) + 1);
    int line_tag = 0;
    std::vector<int> loop_tags;
    std::vector<std::array<int, 2>> line_nodes;  // per line tag - 1
    for (const auto& l : loops) {
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

    gmsh::model::mesh::getNodes(node_tags, coords, param, -1, -1, false, false);
    gmsh::model::mesh::getElements(etypes, etags, enodes, 2, surf);
  });

  GmshRecombined ans;
  std::unordered_map<std::size_t, int> tag_to_pos;
  for (size_t i = 0; i < node_tags.size(); ++i) tag_to_pos[node_tags[i]] = int(i);
  std::unordered_map<std::size_t, int> tag_to_new;
  auto node_of = [&](std::size_t tag) {
    auto it = tag_to_new.find(tag);
    if (it != tag_to_new.end()) return it->second;
    auto p = tag_to_pos.find(tag);
    if (p == tag_to_pos.end()) throw ExternalError("Gmsh recombination returned an element with an unknown node");
    int idx = int(ans.nodes.size());
    ans.nodes.emplace_back(coords[3 * p->second], coords[3 * p->second + 1]);
    tag_to_new[tag] = idx;
    return idx;
  };
  for (size_t k = 0; k < etypes.size(); ++k) {
    int nv = etypes[k] == 2 ? 3 : etypes[k] == 3 ? 4 : 0;
    if (nv == 0) throw ExternalError("Gmsh recombination returned an element of type " + std::to_string(etypes[k]));
    for (size_t e = 0; e < etags[k].size(); ++e) {
      Cell c;
      c.nv = nv;
      for (int i = 0; i < nv; ++i) c.v[i] = node_of(enodes[k][nv * e + i]);
      ans.cells.push_back(c);
    }
  }
  return ans;
}

}  // namespace quadapt
