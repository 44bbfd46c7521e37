#include "mesh/validate.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "core/error.hpp"
#include "core/format.hpp"
#include "mesh/curved.hpp"
#include "mesh/label.hpp"
#include "mesh/topology.hpp"

namespace quadapt {

namespace {

using Key = std::pair<int, int>;
Key key(int a, int b) { return a < b ? Key{a, b} : Key{b, a}; }

std::string list(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

/// The problem of one cell ("" when valid), and whether it is only ordered clockwise.
struct CellProblem {
  std::string text;
  bool clockwise = false;
};

/// Geometric check of one cell: "" when valid, else the problem.
/// Corner Jacobian at vertex k: cross(v[k+1] - v[k], v[k-1] - v[k]) (4 det J of the bilinear
/// map at that corner for a quad, 2 * area for a triangle). Negative: inverted. Zero (below
/// 1e-12 times the squared longest edge) or zero area: degenerate.
CellProblem cell_problem(const Mesh& m, int c) {
  const Cell& cell = m.cells[c];
  double longest2 = 0;
  for (int k = 0; k < cell.nv; ++k)
    longest2 = std::max(longest2, (m.nodes[cell.v[(k + 1) % cell.nv]] - m.nodes[cell.v[k]]).squaredNorm());
  const double tol = 1e-12 * longest2;
  if (longest2 == 0) return {"degenerate: all its vertices coincide"};
  int negative = 0, first_negative = -1;
  double twice_area = 0;  // signed (shoelace): > 0 counter-clockwise
  for (int k = 0; k < cell.nv; ++k) {
    const Vec2& p = m.nodes[cell.v[k]];
    const Vec2& q = m.nodes[cell.v[(k + 1) % cell.nv]];
    const Vec2& o = m.nodes[cell.v[0]];  // about a vertex: absolute coordinates lose |x|^2 eps
    twice_area += (p - o).x() * (q - o).y() - (q - o).x() * (p - o).y();
    Vec2 a = q - p;
    Vec2 b = m.nodes[cell.v[(k + cell.nv - 1) % cell.nv]] - p;
    if (a.x() * b.y() - a.y() * b.x() < -tol && negative++ == 0) first_negative = k;
  }
  if (negative > 0) {
    const std::string corner = std::to_string(first_negative + 1) + " " + point_text(m.nodes[cell.v[first_negative]]);
    if (negative == cell.nv) return {"inverted (ordered clockwise: every corner's Jacobian is negative)", true};
    if (negative == 1 && twice_area > tol)  // a dart: one reflex corner, the outline counter-clockwise
      return {"non-convex: reflex angle at corner " + corner + " (a quad must be convex)"};
    return {"inverted: negative Jacobian at corner " + corner};
  }
  // a curved map folded through itself has a negative area, not a zero one (it said "zero area")
  if (const double a = cell_area(m, c); a < -tol)
    return {"inverted: its curved map folds (signed area " + sci(a) + " < 0)"};
  else if (a <= tol)
    return {"degenerate: zero area"};
  for (int k = 0; k < cell.nv; ++k) {
    const Vec2& p = m.nodes[cell.v[k]];
    Vec2 a = m.nodes[cell.v[(k + 1) % cell.nv]] - p;
    Vec2 b = m.nodes[cell.v[(k + cell.nv - 1) % cell.nv]] - p;
    if (a.x() * b.y() - a.y() * b.x() <= tol)
      return {"degenerate: zero Jacobian at corner " + std::to_string(k + 1) + " " + point_text(p) + " (vertices in line)"};
  }
  return {};
}

}  // namespace

std::string cell_shape_problem(const Mesh& m, int c) { return cell_problem(m, c).text; }

void validate_mesh(const Mesh& m, const std::string& path, const ValidateOptions& opt) {
  auto fail = [&](const std::string& problem) { throw InputError(path, problem); };
  const int nc = m.num_cells(), nn = m.num_nodes();
  if (nc == 0)
    fail(m.boundary.empty() ? "the mesh has no cells (no triangles or quadrangles)"
                            : "the mesh has no cells (no triangles or quadrangles), only boundary lines: Gmsh saves only "
                              "the elements of physical groups, so add a Physical Surface holding the cells");

  for (int i = 0; i < nn; ++i)
    if (!std::isfinite(m.nodes[i].x()) || !std::isfinite(m.nodes[i].y()))
      fail("node " + std::to_string(i + 1) + " has a non-finite coordinate " + point_text(m.nodes[i]));
  for (int c = 0; c < nc; ++c) {
    const Cell& cell = m.cells[c];
    if (cell.nv != 3 && cell.nv != 4) fail("cell " + std::to_string(c + 1) + " has " + std::to_string(cell.nv) + " vertices");
    for (int k = 0; k < cell.nv; ++k)
      if (cell.v[k] < 0 || cell.v[k] >= nn)
        fail("cell " + std::to_string(c + 1) + " refers to node " + std::to_string(cell.v[k] + 1) + ", which does not exist (" +
             std::to_string(nn) + " nodes)");
  }

  const int ntri = m.num_triangles(), nquad = m.num_quads();
  if (opt.require == CellKind::Quads && ntri > 0) {
    int c = 0;
    while (m.cells[c].nv != 3) ++c;
    fail(cell_label(m, c) + " is a triangle, but quadrilaterals are required (" + std::to_string(ntri) + " triangles, " +
         std::to_string(nquad) + " quadrilaterals; " +
         (nquad == 0 ? std::string("in Gmsh: Recombine Surface, or recombine TRI.msh -o QUAD.msh)")
                     : std::string("a quad-dominant mesh: in Gmsh add Mesh.RecombinationAlgorithm = 2 (full-quad) or "
                                   "Mesh.SubdivisionAlgorithm = 1 (all quads by splitting); recombine takes "
                                   "all-triangle meshes)")));
  }
  if (opt.require == CellKind::Triangles && nquad > 0) {
    int c = 0;
    while (m.cells[c].nv != 4) ++c;
    fail(cell_label(m, c) + " is a quadrilateral, but triangles are required (" + std::to_string(nquad) +
         " quadrilaterals, " + std::to_string(ntri) + " triangles)");
  }

  int bad = 0, first_bad = -1, clockwise = 0;
  std::string first_problem;
  for (int c = 0; c < nc; ++c) {
    CellProblem p = cell_problem(m, c);
    if (p.text.empty()) continue;
    if (p.clockwise) ++clockwise;
    if (bad++ == 0) {
      first_bad = c;
      first_problem = std::move(p.text);
    }
  }
  if (clockwise == nc)
    fail("every cell is ordered clockwise; quadapt needs counter-clockwise cells: reverse the mesh (Gmsh: "
         "ReverseMesh Surface{...}; in the .geo, or a counter-clockwise Curve Loop)");
  if (bad > 0 && bad == clockwise && bad > 1)  // only orientation is wrong, in part of the mesh
    fail(cell_label(m, first_bad) + " is " + first_problem + " (" + std::to_string(bad) + " of " + std::to_string(nc) +
         " cells, all of them ordered clockwise: a surface meshed clockwise beside counter-clockwise ones? In Gmsh: "
         "ReverseMesh Surface{...}; for it, or a counter-clockwise Curve Loop)");
  if (bad > 0)
    fail(cell_label(m, first_bad) + " is " + first_problem +
         (bad > 1 ? " (" + std::to_string(bad) + " invalid cells in all)" : ""));

  if (m.is_curved()) {
    const int q = m.geometric_order();
    if (!opt.allow_curved)
      fail("the mesh has curved cells (geometric order " + std::to_string(q) +
           "); this tool supports only straight-sided cells (order 1) so far; for its vertex view (straight cells "
           "through the same vertices, fields kept) run: meshconvert " + (path.empty() ? std::string("IN.msh") : path) +
           " --order 1 -o STRAIGHT.msh");
    if (q > kMaxGeometricOrder || !m.all_quads()) fail("curved cells must be quads of order 2 to " + std::to_string(kMaxGeometricOrder));
    if (m.curved.points.size() != static_cast<size_t>(nc) * m.curved.per_cell())
      fail("curved geometry has " + std::to_string(m.curved.points.size()) + " control points, expected " +
           std::to_string(nc) + " cells x " + std::to_string(m.curved.per_cell()));
    const int corner[4] = {0, q, q + (q + 1) * q, (q + 1) * q};
    for (int c = 0; c < nc; ++c)
      for (int k = 0; k < 4; ++k)
        if (m.cell_points(c)[corner[k]] != m.nodes[m.cells[c].v[k]])
          fail(cell_label(m, c) + ": curved control point of corner " + std::to_string(k + 1) + " is not its vertex");
    const ScaledJacobian sj = min_scaled_jacobian(m);
    if (!(sj.min > 0))
      fail(cell_label(m, sj.cell) + " is invalid: its curved map has a non-positive Jacobian (scaled Jacobian " +
           std::to_string(sj.min) + ")");
  }

  const int ng = static_cast<int>(m.groups.size());
  for (size_t e = 0; e < m.boundary.size(); ++e) {
    const BoundaryEdge& be = m.boundary[e];
    if (be.group < 0 || be.group >= ng) fail("boundary edge " + std::to_string(e + 1) + " has no boundary group");
    for (int v : be.v)
      if (v < 0 || v >= nn) fail("boundary edge " + std::to_string(e + 1) + " refers to a node that does not exist");
  }

  Topology topo;
  try {
    topo = build_topology(m);
  } catch (const InputError& e) {
    std::string what = e.what();
    if (what.rfind("mesh: ", 0) == 0) what = what.substr(6);
    fail("invalid topology: " + what);
  }
  std::set<Key> free_keys, cell_keys;
  for (const Face& f : topo.faces) {
    if (!f.is_boundary()) {
      if (!opt.allow_hanging_nodes && !f.is_conforming())
        fail("the mesh is non-conforming (hanging node near " + point_text(0.5 * (f.a + f.b)) +
             "), but this tool needs a conforming mesh");
      continue;
    }
    const Cell& c = m.cells[f.cell[0]];
    free_keys.insert(key(c.v[f.local_edge[0]], c.v[(f.local_edge[0] + 1) % c.nv]));
  }
  // A free edge that overlaps another free edge along one line is an interior interface that
  // is neither conforming nor 2:1 (e.g. four fine faces along one coarse edge): build_topology
  // would treat it as outer boundary, silently decoupling the two sides.
  {
    std::vector<const Face*> free_faces;
    for (const Face& f : topo.faces)
      if (f.is_boundary()) free_faces.push_back(&f);
    for (size_t i = 0; i < free_faces.size(); ++i) {
      const Face& fi = *free_faces[i];
      for (size_t j = i + 1; j < free_faces.size(); ++j) {
        const Face& fj = *free_faces[j];
        const Vec2 d = fi.b - fi.a;
        const double tol = 1e-9 * fi.length;
        auto off = [&](const Vec2& q) { return std::abs(d.x() * (q - fi.a).y() - d.y() * (q - fi.a).x()) / fi.length; };
        if (off(fj.a) > tol || off(fj.b) > tol) continue;
        double s0 = (fj.a - fi.a).dot(d) / d.squaredNorm(), s1 = (fj.b - fi.a).dot(d) / d.squaredNorm();
        double lo = std::max(0.0, std::min(s0, s1)), hi = std::min(1.0, std::max(s0, s1));
        if (hi - lo <= 1e-9) continue;
        const double eq = 1e-9 * fi.length;  // the same edge twice, on other node numbers
        if (((fi.a - fj.b).norm() <= eq && (fi.b - fj.a).norm() <= eq) || ((fi.a - fj.a).norm() <= eq && (fi.b - fj.b).norm() <= eq))
          fail("cells " + std::to_string(fi.cell[0] + 1) + " and " + std::to_string(fj.cell[0] + 1) + " share the edge " +
               point_text(fi.a) + " - " + point_text(fi.b) +
               " on duplicated nodes (two blocks whose shared nodes were not merged): merge them, in Gmsh with "
               "Coherence Mesh; (or Coherence; on the geometry)");
        fail("cells " + std::to_string(fi.cell[0] + 1) + " and " + std::to_string(fj.cell[0] + 1) +
             " meet along " + point_text(0.5 * (fi.a + fi.b)) +
             " without sharing an edge: only conforming or 2:1 (one hanging node) interfaces are supported");
      }
    }
  }
  for (const Cell& c : m.cells)
    for (int k = 0; k < c.nv; ++k) cell_keys.insert(key(c.v[k], c.v[(k + 1) % c.nv]));
  for (const BoundaryEdge& be : m.boundary) {
    const Key k = key(be.v[0], be.v[1]);
    if (free_keys.count(k)) continue;
    fail("boundary edge " + point_text(m.nodes[be.v[0]]) + " - " + point_text(m.nodes[be.v[1]]) + " of '" + m.groups[be.group].name +
         "' is not on the boundary of the mesh (" +
         (cell_keys.count(k) ? "it is an interior edge: a line on a curve inside the domain, which Gmsh saves when the "
                               "file has no physical groups or that curve is in one; put the walls alone in Physical Curves "
                               "and the cells in a Physical Surface"
                             : "it is not an edge of any cell") +
         ")");
  }

  std::vector<std::string> names;
  std::vector<int> edges(ng, 0);
  for (const BoundaryGroup& g : m.groups) names.push_back(g.name);
  for (const BoundaryEdge& be : m.boundary) ++edges[be.group];
  for (const std::string& want : opt.required_groups) {
    int g = m.find_group(want);
    if (g < 0)
      fail("boundary '" + want + "' not found (" + (names.empty() ? std::string("the mesh has no boundary groups") : "boundaries: " + list(names)) + ")");
    if (edges[g] == 0) fail("boundary '" + want + "' has no edges");
  }

  std::vector<std::string> fields;
  for (const CellField& f : m.cell_fields) {
    fields.push_back(f.name);
    if (f.ncomp < 1 || f.values.size() != static_cast<size_t>(nc) * f.ncomp)
      fail("field '" + f.name + "' has " + std::to_string(f.values.size()) + " values, expected " + std::to_string(nc) +
           " cells x " + std::to_string(f.ncomp) + " components");
  }
  for (const CellNodeField& f : m.cell_node_fields) {
    fields.push_back(f.name);
    if (f.ncomp < 1 || f.per_cell < 1 || f.values.size() != static_cast<size_t>(nc) * f.per_cell * f.ncomp)
      fail("field '" + f.name + "' has " + std::to_string(f.values.size()) + " values, expected " + std::to_string(nc) +
           " cells x " + std::to_string(f.per_cell) + " points x " + std::to_string(f.ncomp) + " components");
    if (f.degree >= 0 && f.per_cell != (f.degree + 1) * (f.degree + 1))
      fail("field '" + f.name + "' of degree " + std::to_string(f.degree) + " has " + std::to_string(f.per_cell) +
           " values per cell, expected " + std::to_string((f.degree + 1) * (f.degree + 1)));
  }
  auto finite = [&](const std::string& name, const std::vector<double>& v, size_t per_cell) {
    for (size_t i = 0; i < v.size(); ++i)
      if (!std::isfinite(v[i])) fail("field '" + name + "' is not finite in cell " + std::to_string(i / per_cell + 1));
  };
  for (const CellField& f : m.cell_fields) finite(f.name, f.values, f.ncomp);
  for (const CellNodeField& f : m.cell_node_fields) finite(f.name, f.values, size_t(f.per_cell) * f.ncomp);
  for (const std::string& want : opt.required_fields)
    if (!m.cell_field(want) && !m.cell_node_field(want))
      fail("field '" + want + "' not found (" + (fields.empty() ? std::string("the file has no fields") : "fields: " + list(fields)) + ")");
}

}  // namespace quadapt
