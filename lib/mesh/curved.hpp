#pragma once
// Curved (high-order) quads: the Lagrange map of geometric order q (q = 1..6) of a cell, and
// the correspondence with Gmsh's node ordering (MSH types 3, 10, 36, 37, 38, 47 for quads; 1, 8,
// 26, 27, 28, 62 for lines).
//
// Convention: a curved cell's map is x(xi, eta) = sum_{i,j} X_{i + (q+1) j} l_i(xi) l_j(eta)
// on the reference square [-1,1]^2, l_i the degree-q Lagrange polynomials through the
// equispaced points xi_i = -1 + 2 i / q. The control points X (Mesh::curved.points, (q+1)^2 per
// cell, lexicographic) interpolate the cell: corner X_0, X_q, X_{(q+1)^2-1}, X_{q(q+1)} are the
// vertices v[0], v[1], v[2], v[3]; edge e's interior points lie on the curved edge e. For
// q = 1 the map is the bilinear map of mesh.hpp. Shared edges of neighbouring cells carry the
// same points (in opposite order), so the mesh is watertight.
//
// Gmsh's ordering (documented in the Gmsh reference manual, "Node ordering"): corners 0..3;
// then for each edge 0-1, 1-2, 2-3, 3-0 its q-1 interior nodes in the edge's direction; then
// the (q-1)^2 interior nodes, recursively ordered like a quad of order q-2 (for q = 3:
// (-1/3,-1/3), (1/3,-1/3), (1/3,1/3), (-1/3,1/3)). A line of order q: end points 0, 1, then
// its interior nodes from node 0 to node 1.
#include <Eigen/Core>
#include <vector>

#include "mesh/mesh.hpp"

namespace quadapt {

/// Highest geometric order supported (Gmsh's 49-node quadrangle). Orders 5 and 6 are there for
/// super-parametric cells: p = 4 needs q = 6 for a wall functional at rate 2p (docs/curved.md).
constexpr int kMaxGeometricOrder = 6;

/// Values l[0..q] and derivatives dl[0..q] at x of the Lagrange polynomials through the q+1
/// equispaced points of [-1, 1] (q >= 1).
void equispaced_lagrange(int q, double x, double* l, double* dl);

/// perm[k] = lexicographic index (i + (q+1) j) of Gmsh's k-th node of a quad of order q.
std::vector<int> gmsh_quad_node_order(int q);
/// MSH element type of a quad / line of order q (3, 10, 36, 37, 38, 47 / 1, 8, 26, 27, 28, 62);
/// -1 for other q.
int gmsh_quad_type(int q);
int gmsh_line_type(int q);

/// Lexicographic indices of the q+1 control points of local edge e of a cell (from v[e] to
/// v[(e+1) % 4], end points included).
std::vector<int> edge_control_points(int q, int e);

/// The map of one cell (curved or not) of a quad mesh: evaluates x(xi, eta) and its Jacobian.
/// Cheap to construct; refers to the mesh's storage.
class CellMap {
 public:
  CellMap(const Mesh& m, int c);
  /// The map of order q >= 2 through the (q+1)^2 control points X (lexicographic; the caller
  /// keeps them alive), e.g. a cell's points mapped into a frame's metric space.
  CellMap(int q, const Vec2* X);
  int order() const { return q_; }
  Vec2 map(double xi, double eta) const;
  /// Columns of the Jacobian: t1 = dx/dxi, t2 = dx/deta; returns det J.
  double jacobian(double xi, double eta, Vec2& t1, Vec2& t2) const;

 private:
  int q_;
  const Vec2* X_;      // (q+1)^2 control points (curved) ...
  Vec2 corner_[4];     // ... or the 4 vertices (q = 1)
};

/// Reference point (xi, eta) of parameter s in [0, 1] along local edge e (s = 0 at v[e], 1 at
/// v[(e+1) % 4]); d(xi, eta)/ds is (2,0), (0,2), (-2,0), (0,-2) for e = 0..3.
void edge_reference_point(int e, double s, double& xi, double& eta);

/// Geometry of local edge e of the cell at parameter s: the point x, the outward unit normal n
/// (the cell is counter-clockwise: n = (T_y, -T_x)/|T| with T = dx/ds) and |dx/ds| (returned).
double edge_geometry(const CellMap& G, int e, double s, Vec2& x, Vec2& n);

/// Gives every cell of a straight-sided all-quad mesh (q = 1) the control points of order q on
/// its bilinear map (the same geometry, now with q-order storage). Used to build curved test
/// meshes (then move the boundary points) and for super-parametric experiments.
void elevate_geometric_order(Mesh& m, int q);

/// Minimum over cells of (min det J) / (max det J) sampled on the (2q+2)^2 equispaced points
/// of the reference square, corners included (the scaled Jacobian of the map; 1 for a
/// parallelogram, <= 0 for an invalid cell), and the cell where it occurs. A cell whose samples
/// are all positive but whose det J is not certified positive (certify_jacobian) gets
/// certificate.lowest / max det J (<= 0) instead: the samples cannot see a fold between them.
struct ScaledJacobian {
  double min = 1;
  int cell = -1;
};
ScaledJacobian min_scaled_jacobian(const Mesh& m);

/// Whether det J of curved cell c (order q >= 2) is positive on the whole reference square,
/// certified rather than sampled: det J = x_xi y_eta - x_eta y_xi is a polynomial of degree 2q-1
/// in each of xi, eta, so its values on a 2q x 2q equispaced grid give its Bernstein
/// coefficients on [-1, 1]^2 exactly, and det J lies between their minimum and maximum. Where
/// the minimum coefficient is not positive the square is halved (de Casteljau, alternately in xi
/// and eta) up to kCertifyDepth times; a sub-square's corner coefficients are det J's values
/// there. `positive` false: a point where det J <= 0 was found, `lowest` is det J there. A piece
/// still undecided at the depth limit (1/4096 of the cell's side: det J positive at every point
/// met but within its coefficients' spread of 0, a near-degenerate cell) keeps `positive` and
/// sets `undecided`.
struct JacobianCertificate {
  bool positive = true;
  bool undecided = false;
  double lowest = 0;  ///< the smallest det J at a point of the cell met (sub-square corners)
};
JacobianCertificate certify_jacobian(const Mesh& m, int c);
constexpr int kCertifyDepth = 24;

}  // namespace quadapt
