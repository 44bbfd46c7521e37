#include "case/boundary_conditions.hpp"

#include "mesh/label.hpp"

namespace quadapt {

std::vector<GroupCondition> group_conditions(const Case& cs, const Mesh& mesh) {
  std::vector<int> edges(mesh.groups.size(), 0);
  for (const BoundaryEdge& e : mesh.boundary)
    if (e.group >= 0 && e.group < static_cast<int>(edges.size())) ++edges[e.group];
  std::vector<GroupCondition> out;
  for (size_t g = 0; g < mesh.groups.size(); ++g) {
    if (edges[g] == 0) continue;
    const BoundaryGroup& bg = mesh.groups[g];
    GroupCondition c;
    c.group = static_cast<int>(g);
    c.name = bg.name;
    c.tag = bg.tag;
    c.edges = edges[g];
    c.dirichlet = cs.is_dirichlet(bg.name);
    c.case_data = c.dirichlet ? cs.dirichlet_value(bg.name) != nullptr : cs.neumann_value(bg.name) != nullptr;
    c.functional = cs.has_functional() && cs.functional_boundary == bg.name;
    c.from_free_edges = bg.from_free_edges;
    out.push_back(c);
  }
  return out;
}

std::string free_edge_warning(const Case& cs, const Mesh& mesh, const std::vector<GroupCondition>& groups,
                              const std::string& mesh_path) {
  if (cs.dirichlet_all) return "";  // every group Dirichlet with u_exact: nothing falls through
  bool file_lines = false;
  for (const GroupCondition& g : groups) file_lines = file_lines || !g.from_free_edges;
  if (!file_lines) return "";  // a file without boundary lines: naming its free edges is the documented way
  std::string names;
  int edges = 0, count = 0;
  std::vector<char> flagged(mesh.groups.size(), 0);
  for (const GroupCondition& g : groups) {
    if (!g.from_free_edges || g.dirichlet || g.case_data || g.functional) continue;
    names += (names.empty() ? "'" : ", '") + g.name + "'";
    edges += g.edges;
    ++count;
    flagged[g.group] = 1;
  }
  if (count == 0) return "";
  std::string where;  // the first such edge, to find it in Gmsh
  for (const BoundaryEdge& e : mesh.boundary)
    if (e.group >= 0 && flagged[e.group]) {
      where = point_text(mesh.nodes[e.v[0]]) + " - " + point_text(mesh.nodes[e.v[1]]);
      break;
    }
  return mesh_path + ": " + std::to_string(edges) + " boundary edge" + (edges == 1 ? "" : "s") +
         " carry no line of the file (first: " + where + "); quadapt made " + (count == 1 ? "the group " : "the groups ") +
         names + " of them, which " + cs.path +
         " does not name, so they get the natural condition with the exact solution's flux: put them in a Physical "
         "Curve, or name the group in the case's \"dirichlet\" or \"neumann\"";
}

std::string conditions_text(const std::vector<GroupCondition>& groups) {
  std::string s;
  for (const GroupCondition& g : groups) {
    if (!s.empty()) s += "; ";
    s += g.name + ": " + (g.dirichlet ? "Dirichlet" : "natural") + " (" + (g.case_data ? "case" : "exact") +
         (g.dirichlet ? " data" : " flux") + ")";
    if (g.functional) s += ", J";
    if (g.from_free_edges) s += ", added from free edges";
  }
  return s.empty() ? "none" : s;
}

}  // namespace quadapt
