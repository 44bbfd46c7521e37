#pragma once
// The 2D mesh of quadapt: 4-node quads and/or 3-node triangles, boundary edges
// grouped into named physical curves, and per-cell fields. Conforming and non-conforming
// (hanging-node, 2:1) quad meshes are both valid: a hanging node is simply a node that lies on
// the interior of a neighbour's edge; face connectivity is derived in mesh/topology.hpp.
//
// Conventions
//  - Node and cell indices are 0-based and contiguous (file tags are renumbered on read).
//  - Cells are counter-clockwise. A quad's vertices v[0..3] map to the reference square
//    [-1,1]^2 corners (-1,-1), (1,-1), (1,1), (-1,1) — the same as Gmsh's reference quad.
//    Local edge e of a cell joins v[e] and v[(e+1) % nv].
//  - Curved quads (geometric order q = 2..6; mesh/curved.hpp) keep the vertex-only view above
//    unchanged — nodes holds only vertices, Cell::v the corners — and add the control points of
//    each cell's Lagrange map in Mesh::curved. Tools that need only vertices ignore it; tools
//    that integrate on cells must either use the curved map (mesh/curved.hpp CellMap) or
//    refuse curved meshes (validate_mesh does unless ValidateOptions::allow_curved).
//  - Fields are stored per cell (see mesh/fields.hpp) and travel with the mesh through I/O.
#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "mesh/fields.hpp"

namespace quadapt {

using Vec2 = Eigen::Vector2d;

/// One cell: a triangle (nv = 3) or a quad (nv = 4). v[3] is -1 for triangles.
struct Cell {
  std::array<int, 4> v{{-1, -1, -1, -1}};
  int nv = 4;
  bool is_quad() const { return nv == 4; }
};

/// A boundary edge (2-node line) belonging to the physical curve groups[group].
struct BoundaryEdge {
  std::array<int, 2> v{{-1, -1}};
  int group = 0;
};

/// A physical group of boundary curves. `tag` is the physical tag written to files; `name` is
/// the boundary-condition / functional name ("left", "bottom", "boundary_1", ...).
struct BoundaryGroup {
  int tag = 0;
  std::string name;
  /// Made by complete_boundary (mesh/boundary.hpp) from free edges no line of the file covered,
  /// not read from the file; written back as an ordinary physical group (so false once re-read).
  bool from_free_edges = false;
};

/// High-order geometry of the cells (mesh/curved.hpp): order q and, per cell, (q+1)^2 control
/// points (lexicographic on the equispaced reference grid). order 1 and no points: straight.
struct CurvedGeometry {
  int order = 1;
  std::vector<Vec2> points;  ///< #cells * (order+1)^2
  int per_cell() const { return (order + 1) * (order + 1); }
};

struct Mesh {
  std::vector<Vec2> nodes;               ///< #nodes, physical coordinates (x, y)
  std::vector<Cell> cells;               ///< #cells
  std::vector<BoundaryEdge> boundary;    ///< boundary edges with their group index
  std::vector<BoundaryGroup> groups;     ///< boundary groups; BoundaryEdge::group indexes this
  std::string domain_name = "domain";    ///< physical name of the 2D region
  int domain_tag = 1;                    ///< physical tag of the 2D region

  CurvedGeometry curved;                 ///< empty (order 1) for straight-sided cells

  std::vector<CellField> cell_fields;          ///< $ElementData views (theta, rho, B, h, Vinv, dwr, ...)
  std::vector<CellNodeField> cell_node_fields; ///< $ElementNodeData views (the DG solution u, ...)
  /// The size convention of the frame field "Vinv" as the file states it (section
  /// $FrameConvention, one word; empty when the file has none, e.g. PHiLiP's). Interpreted by
  /// frame/frame.hpp only; travels with the fields and is cleared with them.
  std::string frame_convention;
  /// The PDE the solution field was solved with (section $SolvedCase, one line of JSON written
  /// by dgsolve: case/solved_case.hpp; empty when the file has none). Travels with the fields
  /// and is cleared with them.
  std::string solved_case;

  int num_nodes() const { return static_cast<int>(nodes.size()); }
  int num_cells() const { return static_cast<int>(cells.size()); }
  int num_quads() const;
  int num_triangles() const;
  bool all_quads() const { return num_triangles() == 0; }
  bool all_triangles() const { return num_quads() == 0; }
  /// Geometric order q of the cells (1: straight-sided).
  int geometric_order() const { return curved.order; }
  bool is_curved() const { return curved.order > 1; }
  /// The (q+1)^2 control points of curved cell c (is_curved() only).
  const Vec2* cell_points(int c) const { return curved.points.data() + static_cast<size_t>(c) * curved.per_cell(); }

  /// Index of the boundary group called `name`, or -1.
  int find_group(const std::string& name) const;
  /// Index of a group, creating it (with the next free tag) when absent.
  int group_index(const std::string& name);
  /// A curve tag no group uses: max(lowest, largest group tag + 1), or (when the largest is
  /// INT_MAX, as a file may say) the smallest unused tag >= 1.
  int free_tag(int lowest = 1) const;

  /// Field look-ups; nullptr when absent.
  const CellField* cell_field(const std::string& name) const;
  CellField* cell_field(const std::string& name);
  const CellNodeField* cell_node_field(const std::string& name) const;
  CellNodeField* cell_node_field(const std::string& name);
  /// Adds or replaces a field of the same name (checks its size against num_cells()).
  void set_field(CellField f);
  void set_field(CellNodeField f);
  /// Removes every field (e.g. before writing a remeshed geometry).
  void clear_fields() {
    cell_fields.clear();
    cell_node_fields.clear();
    frame_convention.clear();
    solved_case.clear();
  }
  /// For messages: the fields' names, cell fields first, node fields marked "(node field)"
  /// ("p, theta, u (node field)"); "none" when there are none.
  std::string field_list() const;
};

// ----------------------------------------------------------------------------- geometry

/// Signed area of cell c (positive when counter-clockwise). Quads: shoelace over 4 vertices;
/// curved quads: Gauss quadrature of det J (exact for the polynomial map).
double cell_area(const Mesh& m, int c);
/// Sum of cell areas.
double total_area(const Mesh& m);
/// Centroid (area-weighted) of cell c.
Vec2 cell_centroid(const Mesh& m, int c);
/// Bilinear (quad) or linear (triangle) map of reference point (xi, eta) to physical space
/// (the Lagrange map of order q for curved quads).
/// Quads: reference square [-1,1]^2. Triangles: reference triangle (0,0),(1,0),(0,1).
Vec2 map_to_physical(const Mesh& m, int c, double xi, double eta);
/// Jacobian d(x,y)/d(xi,eta) (2x2, columns = d/dxi, d/deta) of that map at (xi, eta).
Eigen::Matrix2d map_jacobian(const Mesh& m, int c, double xi, double eta);
/// Longest/shortest edge lengths and diameter-like size sqrt(area) of cell c.
double cell_size(const Mesh& m, int c);
/// Euclidean distance from p to the segment a-b (to a when a == b).
double segment_distance(const Vec2& p, const Vec2& a, const Vec2& b);

// ----------------------------------------------------------------------------- builders

/// Structured nx-by-ny quad grid on [x0,x1] x [y0,y1], boundary groups bottom/right/top/left
/// (tags 1..4), cells ordered row by row from the bottom-left. Node coordinates are exact
/// (x0 + i*(x1-x0)/nx computed directly, no accumulation).
Mesh make_structured_quads(int nx, int ny, double x0 = 0, double x1 = 1, double y0 = 0,
                           double y1 = 1);

/// Same grid with each interior node moved by a uniform random offset of at most
/// `amplitude` times the local spacing in each direction (seeded, deterministic).
Mesh make_perturbed_quads(int nx, int ny, double amplitude, unsigned seed);

}  // namespace quadapt
