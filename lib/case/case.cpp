#include "case/case.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/format.hpp"

namespace quadapt {

namespace {

using nlohmann::json;

/// A coefficient of D or c is 0 or of magnitude 1e-100..1e100: beyond, the adjoint's products of
/// residual and adjoint over- or underflow (measured: D = 1e200 I gave sum_eta = 0); the linear
/// systems themselves are scaled (linear_solver.hpp system_scale).
void check_magnitude(double v, const std::string& path, const char* key) {
  if (v != 0 && !(std::abs(v) >= 1e-100 && std::abs(v) <= 1e100))
    throw InputError(path, std::string("key '") + key + "': entry " + sci(v) +
                               " is outside 1e-100..1e100 in magnitude (write 0, or rescale the problem)");
}

double constant_value(const json& v, const std::string& path, const std::string& key) {
  if (v.is_number()) return v.get<double>();
  if (v.is_string()) {
    try {
      return parse_constant(v.get<std::string>());
    } catch (const InputError& e) {
      throw InputError(path, "key '" + key + "': " + e.what());
    }
  }
  throw InputError(path, "key '" + key + "': expected a number or a constant expression string, got " + v.dump());
}

/// Parses a map {"name": "expression", ...} of boundary data under `key`.
std::vector<BoundaryData> boundary_data_map(const json& d, const std::string& path, const std::string& key) {
  std::vector<BoundaryData> out;
  for (auto it = d.begin(); it != d.end(); ++it) {
    if (it.key().empty()) throw InputError(path, "key '" + key + "' has an empty boundary name");
    BoundaryData bd;
    bd.boundary = it.key();
    if (it.value().is_number()) bd.source = it.value().dump();
    else if (it.value().is_string()) bd.source = it.value().get<std::string>();
    else
      throw InputError(path, "key '" + key + "." + it.key() + "': expected an expression string, got " + it.value().dump());
    try {
      bd.expr = parse_expression(bd.source);
    } catch (const InputError& e) {
      throw InputError(path, "key '" + key + "." + it.key() + "': " + e.what());
    }
    out.push_back(std::move(bd));
  }
  return out;
}

const BoundaryData* find_data(const std::vector<BoundaryData>& v, const std::string& name) {
  for (const BoundaryData& d : v)
    if (d.boundary == name) return &d;
  return nullptr;
}

}  // namespace

const BoundaryData* Case::dirichlet_value(const std::string& group_name) const {
  return find_data(dirichlet_data, group_name);
}
const BoundaryData* Case::neumann_value(const std::string& group_name) const {
  return find_data(neumann_data, group_name);
}

bool Case::is_dirichlet(const std::string& group_name) const {
  if (dirichlet_all) return true;
  return std::find(dirichlet.begin(), dirichlet.end(), group_name) != dirichlet.end();
}

Case parse_case(const std::string& text, const std::string& path) {
  json j;
  // a key given twice in one object: nlohmann keeps the last silently, so a typo'd copy of
  // "exact" would win unseen; found while parsing (a stack of the keys seen per open object)
  std::vector<std::vector<std::string>> seen;
  std::string duplicate;
  const json::parser_callback_t dup = [&](int, json::parse_event_t ev, json& parsed) {
    if (ev == json::parse_event_t::object_start) seen.emplace_back();
    else if (ev == json::parse_event_t::object_end && !seen.empty()) seen.pop_back();
    else if (ev == json::parse_event_t::key && !seen.empty()) {
      const std::string k = parsed.get<std::string>();
      if (std::find(seen.back().begin(), seen.back().end(), k) != seen.back().end() && duplicate.empty()) duplicate = k;
      seen.back().push_back(k);
    }
    return true;
  };
  try {
    j = json::parse(text, dup);
  } catch (const json::exception& e) {
    throw InputError(path, std::string("not valid JSON: ") + e.what());
  }
  if (!duplicate.empty()) throw InputError(path, "key '" + duplicate + "' is given twice in one object (the last would win unseen)");
  if (!j.is_object()) throw InputError(path, "a case file must be a JSON object");
  static const std::vector<std::string> known = {"name",      "description", "diffusion", "advection",
                                                 "exact",     "dirichlet",   "neumann",   "functional"};
  for (auto it = j.begin(); it != j.end(); ++it)
    if (std::find(known.begin(), known.end(), it.key()) == known.end())
      throw InputError(path, "unknown key '" + it.key() +
                                 "' (known: name, description, diffusion, advection, exact, dirichlet, neumann, functional)");

  Case cs;
  cs.path = path;
  if (j.contains("name")) {
    if (!j["name"].is_string()) throw InputError(path, "key 'name' must be a string");
    cs.name = j["name"].get<std::string>();
  }
  if (j.contains("description")) {
    if (!j["description"].is_string()) throw InputError(path, "key 'description' must be a string");
    cs.description = j["description"].get<std::string>();
  }
  if (j.contains("diffusion")) {
    const json& d = j["diffusion"];
    if (!d.is_array() || d.size() != 2 || !d[0].is_array() || !d[1].is_array() || d[0].size() != 2 ||
        d[1].size() != 2)
      throw InputError(path, "key 'diffusion' must be a 2x2 array [[a, b], [b, c]]");
    for (int r = 0; r < 2; ++r)
      for (int c = 0; c < 2; ++c) cs.diffusion(r, c) = constant_value(d[r][c], path, "diffusion");
    const Eigen::Matrix2d& D = cs.diffusion;
    if (!D.allFinite()) throw InputError(path, "key 'diffusion' has a non-finite entry");
    for (int r = 0; r < 2; ++r)
      for (int c = 0; c < 2; ++c) check_magnitude(D(r, c), path, "diffusion");
    double scale = D.cwiseAbs().maxCoeff();
    if (std::abs(D(0, 1) - D(1, 0)) > 1e-14 * scale)
      throw InputError(path, "key 'diffusion' must be symmetric ([[a, b], [b, c]])");
    // determinant of D / scale: D's own overflows at 1e200 and underflows at 1e-300
    const Eigen::Matrix2d Dn = scale > 0 ? Eigen::Matrix2d(D / scale) : D;
    if (D(0, 0) < 0 || D(1, 1) < 0 || Dn(0, 0) * Dn(1, 1) - Dn(0, 1) * Dn(1, 0) < -1e-14)
      throw InputError(path, "key 'diffusion' must be positive semi-definite");
  }
  if (j.contains("advection")) {
    const json& c = j["advection"];
    if (!c.is_array() || c.size() != 2) throw InputError(path, "key 'advection' must be an array [cx, cy]");
    for (int r = 0; r < 2; ++r) cs.advection(r) = constant_value(c[r], path, "advection");
    if (!cs.advection.allFinite()) throw InputError(path, "key 'advection' has a non-finite entry");
    for (int r = 0; r < 2; ++r) check_magnitude(cs.advection(r), path, "advection");
  }
  if (!j.contains("exact")) throw InputError(path, "missing key 'exact' (the exact solution u(x, y))");
  if (!j["exact"].is_string()) throw InputError(path, "key 'exact' must be an expression string");
  cs.exact_source = j["exact"].get<std::string>();
  try {
    cs.exact = parse_expression(cs.exact_source);
  } catch (const InputError& e) {
    throw InputError(path, std::string("key 'exact': ") + e.what());
  }

  if (cs.diffusion.isZero(0.0) && cs.advection.isZero(0.0))
    throw InputError(path, "both 'diffusion' and 'advection' are zero: there is no PDE to solve");
  {
    // D of rank 1 (semi-definite, not zero): along its null direction v only advection carries
    // u; with c . v = 0 nothing does, and the solver returned an arbitrary u there (exit 0,
    // L2 error 5 for a solution of size 1; D = [[1,0],[0,0]], c = 0)
    const double scale = cs.diffusion.cwiseAbs().maxCoeff();
    const Eigen::Matrix2d D = scale > 0 ? Eigen::Matrix2d(cs.diffusion / scale) : cs.diffusion;  // scale-free
    if (scale > 0 && std::abs(D(0, 0) * D(1, 1) - D(0, 1) * D(1, 0)) <= 1e-12) {
      const Eigen::Vector2d v = D(0, 0) >= D(1, 1) ? Eigen::Vector2d(-D(0, 1), D(0, 0)).normalized()
                                                   : Eigen::Vector2d(D(1, 1), -D(1, 0)).normalized();
      if (!(std::abs(cs.advection.dot(v)) > 1e-12 * cs.advection.norm()))  // c = 0 included
        throw InputError(path, "key 'diffusion' is singular and 'advection' has no component along its null direction (" +
                                   sci(v.x()) + ", " + sci(v.y()) +
                                   "): u is not determined along it; make D positive definite or add advection there");
    }
  }

  if (j.contains("dirichlet")) {
    const json& d = j["dirichlet"];
    if (d.is_string() && d.get<std::string>() == "all") {
      cs.dirichlet_all = true;
    } else if (d.is_object()) {
      cs.dirichlet_all = false;
      cs.dirichlet_data = boundary_data_map(d, path, "dirichlet");
      for (const BoundaryData& bd : cs.dirichlet_data) cs.dirichlet.push_back(bd.boundary);
    } else {
      if (!d.is_array())
        throw InputError(path, "key 'dirichlet' must be a list of boundary names, a map {name: expression} (or \"all\")");
      cs.dirichlet_all = false;
      for (const json& n : d) {
        if (!n.is_string()) throw InputError(path, "key 'dirichlet' must list boundary names (strings)");
        cs.dirichlet.push_back(n.get<std::string>());
      }
    }
  }
  // pure diffusion fixes u only through Dirichlet data: without any, u is determined up to a
  // constant and the solver returned one at random (exit 0, an error 300x the solution)
  if (!cs.dirichlet_all && cs.dirichlet.empty() && cs.advection.isZero(0.0))
    throw InputError(path, "key 'dirichlet' lists no boundary and there is no advection: u would be determined only "
                           "up to a constant; name at least one Dirichlet boundary");
  if (j.contains("neumann")) {
    const json& d = j["neumann"];
    if (!d.is_object()) throw InputError(path, "key 'neumann' must be a map {boundary name: expression}");
    cs.neumann_data = boundary_data_map(d, path, "neumann");
    for (const BoundaryData& bd : cs.neumann_data)
      if (cs.is_dirichlet(bd.boundary))
        throw InputError(path, "boundary '" + bd.boundary + "' has Neumann data but is a Dirichlet boundary" +
                                   (!cs.dirichlet_all ? ""
                                    : j.contains("dirichlet")
                                        ? " (\"dirichlet\": \"all\" makes every boundary Dirichlet; list the Dirichlet "
                                          "boundaries instead)"
                                        : " (\"dirichlet\" absent means every boundary; list the Dirichlet boundaries)"));
  }
  if (j.contains("functional")) {
    const json& f = j["functional"];
    if (!f.is_object()) throw InputError(path, "key 'functional' must be an object {\"boundary\": NAME}");
    for (auto it = f.begin(); it != f.end(); ++it)
      if (it.key() != "boundary")
        throw InputError(path, "unknown key 'functional." + it.key() + "' (known: boundary)");
    if (!f.contains("boundary") || !f["boundary"].is_string())
      throw InputError(path, "key 'functional' needs \"boundary\": NAME");
    cs.functional_boundary = f["boundary"].get<std::string>();
    if (cs.functional_boundary.empty()) throw InputError(path, "key 'functional.boundary' is empty");
  }
  return cs;
}

Case load_case(const std::string& path) { return parse_case(read_text_file(path), path); }

void check_case_boundaries(const Case& cs, const Mesh& mesh) {
  // edges per name (two groups may share a name; all of them count, as in the solver)
  std::vector<std::pair<std::string, long>> edges;
  for (const auto& g : mesh.groups)
    if (std::find_if(edges.begin(), edges.end(), [&](const auto& e) { return e.first == g.name; }) == edges.end())
      edges.emplace_back(g.name, 0);
  for (const BoundaryEdge& e : mesh.boundary)
    if (e.group >= 0 && e.group < static_cast<int>(mesh.groups.size()))
      for (auto& [name, n] : edges)
        if (name == mesh.groups[e.group].name) ++n;
  auto list = [&] {
    std::string s;
    for (const auto& [name, n] : edges)
      if (n > 0) s += (s.empty() ? "" : ", ") + name;
    return s.empty() ? std::string("none") : s;
  };
  // A name the mesh knows with no edge (a physical group on the wrong curve, or $PhysicalNames
  // without its line elements) would silently drop that Dirichlet data or make J = 0.
  auto check = [&](const std::string& n, const std::string& what) {
    auto it = std::find_if(edges.begin(), edges.end(), [&](const auto& e) { return e.first == n; });
    if (it == edges.end())
      throw InputError(cs.path, what + " '" + n + "' is not a boundary group of the mesh (groups: " + list() + ")" +
                                    (n == "all" ? "; every boundary is written \"dirichlet\": \"all\", a string, not a list" : ""));
    if (it->second == 0)
      throw InputError(cs.path, what + " '" + n + "' is a boundary group of the mesh without any edge (no line of the "
                                "mesh file carries it: a physical curve on the wrong entity, or an MSH 2.2 file saved "
                                "with Mesh.SaveAll, which writes physical tag 0 on every line; save as MSH 4.1); "
                                "groups with edges: " + list());
  };
  for (const std::string& n : cs.dirichlet) check(n, "Dirichlet boundary");
  for (const BoundaryData& bd : cs.neumann_data) check(bd.boundary, "Neumann boundary");
  if (cs.has_functional()) check(cs.functional_boundary, "functional boundary");
}

void check_case_finite(const Case& cs, const Mesh& mesh) {
  const ExactSolution ex(cs);
  std::vector<double> scratch(ex.scratch_size());
  const char* what[] = {"the exact solution", "the exact solution's x-derivative",
                        "the exact solution's y-derivative", "the source term"};
  auto check = [&](const Vec2& x) {
    double out[ExactSolution::NUM_OUTPUTS];
    ex.eval(x.x(), x.y(), out, scratch.data());
    for (int k = 0; k < ExactSolution::NUM_OUTPUTS; ++k)
      if (!std::isfinite(out[k])) {
        throw InputError(cs.path, what[k] + std::string(" of '") + cs.exact_source + "' is not finite at " +
                                      sci_point(x.x(), x.y()) +
                                      " (a point of the mesh)");
      }
  };
  // Where the solver evaluates them (Gauss points, never a node) stands in here as every cell's
  // centroid and every edge's midpoint: an isolated singular point on a node (a corner
  // singularity r^(2/3) sin(2 theta / 3) at a re-entrant corner) is accepted, a singular line
  // along the mesh's edges (1/(x - 0.5) with a node line at x = 0.5) is refused.
  for (int c = 0; c < mesh.num_cells(); ++c) {
    check(cell_centroid(mesh, c));
    const Cell& cell = mesh.cells[c];
    for (int k = 0; k < cell.nv; ++k) check(0.5 * (mesh.nodes[cell.v[k]] + mesh.nodes[cell.v[(k + 1) % cell.nv]]));
  }
  // boundary data: at the midpoint and the two Gauss points of every edge of its boundary (before
  // the solve: a NaN right-hand side used to run the whole solver chain, then blame "a singular
  // system"); not at the nodes, where the solver never evaluates it
  auto check_data = [&](const std::vector<BoundaryData>& data, const char* key) {
    for (const BoundaryData& bd : data)
      for (const BoundaryEdge& e : mesh.boundary) {
        if (e.group < 0 || e.group >= static_cast<int>(mesh.groups.size()) || mesh.groups[e.group].name != bd.boundary)
          continue;
        const Vec2 a = mesh.nodes[e.v[0]], b = mesh.nodes[e.v[1]];
        const double g = 0.5 / std::sqrt(3.0);  // the 2-point Gauss rule's points at 1/2 -+ g
        for (const Vec2& x : {Vec2((0.5 + g) * a + (0.5 - g) * b), Vec2(0.5 * (a + b)), Vec2((0.5 - g) * a + (0.5 + g) * b)}) {
          const double v = evaluate(bd.expr, x.x(), x.y());
          if (std::isfinite(v)) continue;
          throw InputError(cs.path, std::string("key '") + key + "." + bd.boundary + "': '" + bd.source +
                                        "' is not finite at " + sci_point(x.x(), x.y()) + " (a point of that boundary)");
        }
      }
  };
  check_data(cs.dirichlet_data, "dirichlet");
  check_data(cs.neumann_data, "neumann");
}

ExactSolution::ExactSolution(const Case& cs) {
  using O = ExprOp;
  u_ = cs.exact;
  ux_ = differentiate(u_, 0);
  uy_ = differentiate(u_, 1);
  Expr uxx = differentiate(ux_, 0);
  Expr uxy = differentiate(ux_, 1);
  Expr uyy = differentiate(uy_, 1);
  const Eigen::Matrix2d& D = cs.diffusion;
  const Eigen::Vector2d& c = cs.advection;
  auto k = expr_const;
  Expr s = expr_binary(O::Mul, k(D(0, 0)), uxx);
  s = expr_binary(O::Add, s, expr_binary(O::Mul, k(D(0, 1) + D(1, 0)), uxy));
  s = expr_binary(O::Add, s, expr_binary(O::Mul, k(D(1, 1)), uyy));
  s = expr_binary(O::Sub, s, expr_binary(O::Mul, k(c(0)), ux_));
  s = expr_binary(O::Sub, s, expr_binary(O::Mul, k(c(1)), uy_));
  s_ = s;
  prog_ = ExprProgram({u_, ux_, uy_, s_});
  prog_u_ = ExprProgram({u_});
}

double ExactSolution::u(double x, double y) const { return prog_u_.eval(x, y)[0]; }
double ExactSolution::source(double x, double y) const { return prog_.eval(x, y)[S]; }

}  // namespace quadapt
