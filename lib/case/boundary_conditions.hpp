#pragma once
// Which condition each boundary group of a mesh gets from a case (the rules of case/case.hpp:
// "dirichlet" absent = every group Dirichlet; a listed group Dirichlet, its data the case's map
// expression else u_exact; every other group natural, its diffusive flux the case's "neumann"
// expression else the exact solution's), stated per group for dgsolve's report and log, and the
// warning for groups quadapt made itself from free edges that the case leaves natural.
#include <string>
#include <vector>

#include "case/case.hpp"
#include "mesh/mesh.hpp"

namespace quadapt {

/// One boundary group of the mesh and the condition the case gives it.
struct GroupCondition {
  int group = -1;  ///< index into Mesh::groups
  std::string name;
  int tag = 0;
  int edges = 0;                 ///< boundary edges of the group (lines of the file, or added)
  bool dirichlet = false;        ///< else natural (Neumann data + upwind advection)
  bool case_data = false;        ///< data from the case's expression, else from the exact solution
  bool functional = false;       ///< J = int u^2 is taken over this group
  bool from_free_edges = false;  ///< BoundaryGroup::from_free_edges: no line of the file covered it
};

/// Per group of `mesh`, in the mesh's group order (groups without edges are left out).
std::vector<GroupCondition> group_conditions(const Case& cs, const Mesh& mesh);

/// "" or a one-line warning (without "warning: ") when the mesh file has boundary lines of its
/// own (at least one group read from it) and quadapt completed the boundary from free edges
/// into groups the case does not name while it lists its Dirichlet boundaries: those edges then
/// get the natural condition with the exact solution's flux — usually a wall the file tagged on
/// one of its curves only. `mesh_path` names the file.
std::string free_edge_warning(const Case& cs, const Mesh& mesh, const std::vector<GroupCondition>& groups,
                              const std::string& mesh_path);

/// "left: Dirichlet (case data); right: natural (exact flux), J; ..." for the tool's log.
std::string conditions_text(const std::vector<GroupCondition>& groups);

}  // namespace quadapt
