#pragma once
// A test case of the advection-diffusion solver: PDE constants, manufactured solution,
// boundary conditions and functional (docs/design.md §3; thesis eq. 6.2).
//
// The PDE, with the thesis's sign convention (eq. 6.2):
//     div(D grad u) - c . grad u = S      in the domain,
// D a symmetric positive semi-definite 2x2 tensor, c a constant vector. S is derived from the
// exact solution symbolically:  S = D11 u_xx + (D12 + D21) u_xy + D22 u_yy - cx u_x - cy u_y.
//
// Case file (JSON; unknown keys are an error):
//   {
//     "name":        "sshock",                      optional, free text
//     "description": "...",                         optional, free text
//     "diffusion":   [[a, b], [b, c]],              default 0; numbers or constant expressions
//                                                   such as "0.01*pi/e*12"
//     "advection":   [cx, cy],                      default 0; numbers or constant expressions
//     "exact":       "0.75*tanh(4*sin(10*y-5)-24*x+12)",   required: u(x, y)
//     "dirichlet":   ["left", "bottom"],            default: every boundary; data u = u_exact
//               or   {"inner": "0", "outer": "g(x,y)"}   map: boundary name -> data expression
//     "neumann":     {"right": "h(x,y)"}            optional: diffusive flux data D grad u . n
//     "functional":  {"boundary": "right"}          optional: J(u) = integral of u^2 over it
//   }
// Boundaries not listed in "dirichlet" are natural: the diffusive flux D grad u . n (n outward)
// is the "neumann" expression of that boundary, else taken from the exact solution, and the
// advective flux is upwind with the outside state u_exact (the interior trace on outflow).
// On Dirichlet boundaries the data (the map's expression, else u_exact) enters weakly; with
// D = 0 only where c . n < 0. Data expressions are evaluated at the physical quadrature points
// of the mesh's boundary (the polygon for straight cells, the curved map for curved ones), so
// with data that is data a straight-sided wall shows its geometric error.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "case/expression.hpp"
#include "mesh/mesh.hpp"

namespace quadapt {

/// Boundary data given as an expression of (x, y) on one named boundary.
struct BoundaryData {
  std::string boundary;  ///< boundary group name
  std::string source;    ///< the expression text
  Expr expr;
};

struct Case {
  std::string path;  ///< file it was read from (for messages); may be empty
  std::string name;
  std::string description;
  Eigen::Matrix2d diffusion = Eigen::Matrix2d::Zero();  ///< D (symmetric, PSD)
  Eigen::Vector2d advection = Eigen::Vector2d::Zero();  ///< c
  std::string exact_source;                             ///< the "exact" text
  Expr exact;                                           ///< u(x, y)
  bool dirichlet_all = true;                            ///< "dirichlet" absent: every boundary
  std::vector<std::string> dirichlet;                   ///< listed Dirichlet boundary names
  std::vector<BoundaryData> dirichlet_data;  ///< map form of "dirichlet": value g per boundary
  std::vector<BoundaryData> neumann_data;    ///< "neumann": D grad u . n per natural boundary
  std::string functional_boundary;                      ///< empty: no functional

  bool has_functional() const { return !functional_boundary.empty(); }
  /// Whether the boundary group called `group_name` carries Dirichlet data (group_name may be
  /// empty for boundary edges without a group: Dirichlet only when every boundary is).
  bool is_dirichlet(const std::string& group_name) const;
  /// The data expression given for boundary `group_name`, or nullptr (then u_exact's trace,
  /// respectively D grad u_exact . n, is the data).
  const BoundaryData* dirichlet_value(const std::string& group_name) const;
  const BoundaryData* neumann_value(const std::string& group_name) const;
  /// True when D = 0 (pure advection).
  bool advection_only() const { return diffusion.isZero(0.0); }
};

/// Parses a case from JSON text. `path` is used in messages ("PATH: key 'exact': column 7: ...").
/// Throws InputError on malformed JSON, an unknown key, a wrong type, an expression that does
/// not parse (with its column and token), a non-symmetric or indefinite D, or D = 0 and c = 0.
Case parse_case(const std::string& json_text, const std::string& path);

/// Reads and parses a case file.
Case load_case(const std::string& path);

/// Checks that every boundary the case names exists in the mesh (InputError naming the case
/// file, the missing boundary and the mesh's boundary groups).
void check_case_boundaries(const Case& cs, const Mesh& mesh);

/// Checks that the exact solution, its gradient and the source term are finite at every cell
/// centroid and edge midpoint of `mesh` (e.g. log(x-2) on the unit square is not), and the
/// boundary data at the midpoint and Gauss points of their edges: InputError naming the case
/// file, the expression and the point. Not at the nodes, where the solver never evaluates: a
/// corner singularity on a node is a valid case. dg_solve and compute_dwr call it first.
void check_case_finite(const Case& cs, const Mesh& mesh);

/// The exact solution with its derivatives and the source term, compiled for fast evaluation.
/// Outputs, in order: u, u_x, u_y, S.
class ExactSolution {
 public:
  explicit ExactSolution(const Case& cs);
  enum { U = 0, UX = 1, UY = 2, S = 3, NUM_OUTPUTS = 4 };
  /// out[0..3] = u, u_x, u_y, S at (x, y); scratch holds scratch_size() doubles (per thread).
  void eval(double x, double y, double* out, double* scratch) const { prog_.eval(x, y, out, scratch); }
  int scratch_size() const { return prog_.scratch_size(); }
  /// u alone (cheaper: no derivatives); scratch of scratch_size() doubles suffices.
  double eval_u(double x, double y, double* scratch) const {
    double v;
    prog_u_.eval(x, y, &v, scratch);
    return v;
  }
  /// Convenience (allocating) single-value evaluations.
  double u(double x, double y) const;
  double source(double x, double y) const;

  const Expr& u_expr() const { return u_; }
  const Expr& ux_expr() const { return ux_; }
  const Expr& uy_expr() const { return uy_; }
  const Expr& source_expr() const { return s_; }

 private:
  Expr u_, ux_, uy_, s_;
  ExprProgram prog_, prog_u_;
};

}  // namespace quadapt
