#include "mesh/curve_boundary.hpp"

#include <algorithm>
#include <limits>
#include <cmath>
#include <map>

#include "core/error.hpp"
#include "core/format.hpp"
#include "fem/basis.hpp"
#include "mesh/boundary.hpp"
#include "mesh/curved.hpp"
#include "mesh/topology.hpp"

namespace quadapt {

namespace {

struct CurvedEdge {
  Vec2 a, b;                // chord (from node v[0] to v[1] of the boundary edge)
  std::vector<Vec2> delta;  // q+1 displacements at s = i/q (0 at both ends)
  Vec2 lo, hi;              // bounding box of the influence zone
  double rho = 0;
};

}  // namespace

namespace {

// Integral over the degree-q Lagrange curve through pts (equispaced reference parameters, the
// interior ones at curve parameters t[1..q-1] of curve k, t[0] = ta, t[q] = tb) of its signed
// normal distance to the curve, d = (x - c(t*)) . n(t*) with t* the local closest parameter
// (Newton from the parameter interpolated at the same reference point): int d ds. Only points
// and directions of the curve enter (c' and c'' steer Newton; the CAD kernel's parametrisation
// speed need not be accurate).
double normal_distance_integral(const BoundaryGeometry& g, int k, const std::vector<double>& t,
                                const std::vector<Vec2>& pts, const Rule1D& rule) {
  const int q = static_cast<int>(pts.size()) - 1;
  double l[kMaxGeometricOrder + 1], dl[kMaxGeometricOrder + 1];
  double s = 0;
  for (size_t j = 0; j < rule.x.size(); ++j) {
    equispaced_lagrange(q, rule.x[j], l, dl);
    Vec2 x(0, 0), dx(0, 0);
    double tt = 0;
    for (int i = 0; i <= q; ++i) {
      x += l[i] * pts[i];
      dx += dl[i] * pts[i];
      tt += l[i] * t[i];
    }
    Vec2 c = g.point(k, tt), d1 = g.derivative(k, tt);
    for (int it = 0; it < 8; ++it) {
      const Vec2 d2 = g.second_derivative(k, tt);
      const double f = (c - x).dot(d1), df = d1.squaredNorm() + (c - x).dot(d2);
      if (!(df > 0)) break;
      const double step = f / df;
      tt -= step;
      c = g.point(k, tt);
      d1 = g.derivative(k, tt);
      if (std::abs(step) * d1.norm() < 1e-15 * (pts[q] - pts[0]).norm()) break;
    }
    const Vec2 n = Vec2(d1.y(), -d1.x()).normalized();
    s += rule.w[j] * (x - c).dot(n) * dx.norm();
  }
  return s;
}

// Interior parameters of a boundary edge (BoundaryNodes in curve_boundary.hpp): equal steps, or
// for odd q >= 3 with `area` the symmetric stretch whose polynomial edge has the curve's area.
std::vector<double> edge_parameters(const BoundaryGeometry& g, int k, double ta, double tb, int q, bool area,
                                    double& alpha) {
  auto params = [&](double a) {
    std::vector<double> t(q - 1);
    for (int i = 1; i < q; ++i) {
      const double s = static_cast<double>(i) / q;
      t[i - 1] = ta + (tb - ta) * (s + a * (s - 0.5) * s * (1 - s));
    }
    return t;
  };
  alpha = 0;
  if (!area || q % 2 == 0) return params(0);
  static const Rule1D rule = gauss_legendre(16);
  const Vec2 a = g.point(k, ta), b = g.point(k, tb);
  auto residual = [&](double al) {
    std::vector<double> t = params(al);
    const std::vector<Vec2> mid = g.points(k, t);
    std::vector<Vec2> pts{a};
    pts.insert(pts.end(), mid.begin(), mid.end());
    pts.push_back(b);
    t.insert(t.begin(), ta);
    t.push_back(tb);
    return normal_distance_integral(g, k, t, pts, rule);
  };
  // the residual is nearly linear in alpha (alpha ~ (kappa h)^2): a few secant steps
  const double tol = 1e-16 * (b - a).squaredNorm();
  double a0 = 0, r0 = residual(0), a1 = 0.01, r1 = residual(a1);
  for (int it = 0; it < 30 && std::abs(r1) > tol && r1 != r0; ++it) {
    const double a2 = a1 - r1 * (a1 - a0) / (r1 - r0);
    a0 = a1;
    r0 = r1;
    a1 = a2;
    r1 = residual(a1);
  }
  // a stretch that reorders the nodes (|alpha| >= 2 folds s -> s + alpha g(s)) means the edge is far
  // too coarse for its curve: keep equal steps there
  if (!std::isfinite(a1) || std::abs(a1) > 0.5 || std::abs(r1) > std::abs(residual(0))) return params(0);
  alpha = a1;
  return params(a1);
}

// The q - 1 interior control points of a boundary edge a-b whose ends lie on two different curves
// ka, kb of `group` that meet at a shared vertex V with one tangent line and one direction of
// travel (G1: a circle made of arcs): at equal arc-length steps along a -> V -> b, each curve's
// arc length taken as its parameter length times its speed |c'| at V (exact for circles and
// lines). Of the vertices the two curves share (two for a circle drawn as two half arcs) the one
// with the shortest path a -> V -> b, which must be about the chord (at most 2x; a longer one
// would send the edge round the curve). Empty when a and b are not so placed (then the edge is
// refused: a corner of the geometry is not a node).
std::vector<Vec2> across_junction(const BoundaryGeometry& g, const std::vector<int>& group, const Vec2& a,
                                  const Vec2& b, int q, double len) {
  int ka = -1, kb = -1;
  double ta = 0, tb = 0;
  const Vec2 pa = g.closest_point(group, a, &ka, &ta), pb = g.closest_point(group, b, &kb, &tb);
  if (ka < 0 || kb < 0 || ka == kb || (pa - a).norm() > 1e-9 * len || (pb - b).norm() > 1e-9 * len) return {};
  const GeometryCurve &ca = g.curves()[ka], &cb = g.curves()[kb];
  if (ca.closed() || cb.closed()) return {};
  double best = std::numeric_limits<double>::infinity(), tva = 0, tvb = 0, sa = 0, sb = 0, la = 0, lb = 0;
  for (int ea = 0; ea < 2; ++ea)
    for (int eb = 0; eb < 2; ++eb) {
      if (ca.ends[ea] != cb.ends[eb]) continue;
      const double va = ea == 0 ? ca.t0 : ca.t1, vb = eb == 0 ? cb.t0 : cb.t1;
      const Vec2 da = g.derivative(ka, va), db = g.derivative(kb, vb);
      const double na = da.norm(), nb = db.norm();
      if (!(na > 0 && nb > 0)) continue;
      // the directions of travel a -> V on ka and V -> b on kb: parallel and the same way (a cusp,
      // which turns back, is not smooth)
      const Vec2 ua = (va > ta ? 1.0 : -1.0) * da / na, ub = (tb > vb ? 1.0 : -1.0) * db / nb;
      if (std::abs(ua.x() * ub.y() - ua.y() * ub.x()) > 1e-6 || ua.dot(ub) <= 0) continue;
      const double path_a = std::abs(va - ta) * na, path_b = std::abs(tb - vb) * nb;
      if (!(path_a > 0 && path_b > 0) || path_a + path_b >= best) continue;
      best = path_a + path_b;
      tva = va, tvb = vb, sa = na, sb = nb, la = path_a, lb = path_b;
    }
  if (!(best <= 2 * len)) return {};
  std::vector<Vec2> pts;
  for (int i = 1; i < q; ++i) {
    const double s = (la + lb) * i / q;
    pts.push_back(s <= la ? g.point(ka, ta + (tva > ta ? 1 : -1) * s / sa)
                          : g.point(kb, tvb + (tb > tvb ? 1 : -1) * (s - la) / sb));
  }
  return pts;
}

}  // namespace

CurveStats curve_boundary_cells(Mesh& m, const BoundaryGeometry& g, int q, const std::string& path, bool fallback,
                                BoundaryNodes nodes) {
  if (q < 1 || q > kMaxGeometricOrder)
    throw InputError(
        "", "geometric order " + std::to_string(q) + " not supported (1.." + std::to_string(kMaxGeometricOrder) + ")");
  if (m.is_curved())
    throw InputError(path, "the mesh is curved already (geometric order " + std::to_string(m.geometric_order()) + ")");
  if (!m.all_quads()) throw InputError(path, "curved cells must be quads (the mesh has triangles)");
  CurveStats st;
  // 2:1 hanging nodes: they must stay on their coarse edges, so nothing interior moves (the
  // snap moves only boundary nodes, the curving only the boundary cells' own control points; the
  // interior edges stay straight with equispaced control points, which the coarse and the fine
  // side parametrise alike)
  const Topology topo = build_topology(m);
  st.hanging = std::any_of(topo.faces.begin(), topo.faces.end(), [](const Face& f) { return !f.is_conforming(); });
  st.snap = snap_to_geometry(m, g, path, !st.hanging);
  st.order = q;
  if (q == 1) return st;
  const auto curves = group_curves(m, g, path);

  // boundary edges: control points on the curve
  std::map<std::uint64_t, std::vector<Vec2>> on_curve;  // directed edge key (v0 -> v1) -> q+1 points
  std::vector<CurvedEdge> edges;
  for (const auto& e : m.boundary) {
    const Vec2 a = m.nodes[e.v[0]], b = m.nodes[e.v[1]];
    int k = -1;
    g.closest_point(curves[e.group], 0.5 * (a + b), &k);
    const auto& cv = g.curves()[k];
    double ta = g.closest_parameter(k, a), tb = g.closest_parameter(k, b);
    const double len = (b - a).norm();
    std::vector<Vec2> mid;  // the q - 1 interior control points
    if ((g.point(k, ta) - a).norm() > 1e-9 * len || (g.point(k, tb) - b).norm() > 1e-9 * len) {
      // across a smooth junction of two curves of the same group (a circle drawn as four arcs,
      // whose junction the mesh need not have as a node: BAMG drops it), else refused
      mid = across_junction(g, curves[e.group], a, b, q, len);
      if (mid.empty())
        throw InputError(path, "boundary edge " + point_text(a) + " - " + point_text(b) +
                                   " does not lie on one curve of " + g.source() +
                                   " (a corner of the geometry is not a node of the mesh)");
      ++st.junction_edges;
    }
    if (mid.empty()) {  // on one curve
      if (cv.closed()) {  // the short way round
        const double P = cv.t1 - cv.t0;
        if (tb - ta > 0.5 * P) tb -= P;
        if (ta - tb > 0.5 * P) tb += P;
      } else {  // exact corners
        if (ta == cv.t0 || ta == cv.t1)
          ta = (g.point(k, cv.t0) - a).norm() < (g.point(k, cv.t1) - a).norm() ? cv.t0 : cv.t1;
        if (tb == cv.t0 || tb == cv.t1)
          tb = (g.point(k, cv.t0) - b).norm() < (g.point(k, cv.t1) - b).norm() ? cv.t0 : cv.t1;
      }
      double alpha = 0;
      const std::vector<double> t = edge_parameters(g, k, ta, tb, q, nodes == BoundaryNodes::Area, alpha);
      st.max_stretch = std::max(st.max_stretch, std::abs(alpha));
      mid = g.points(k, t);
    }
    std::vector<Vec2> pts{a};
    pts.insert(pts.end(), mid.begin(), mid.end());
    pts.push_back(b);
    CurvedEdge ce;
    ce.a = a;
    ce.b = b;
    ce.rho = len;
    for (int i = 0; i <= q; ++i) {
      Vec2 d = pts[i] - (a + (static_cast<double>(i) / q) * (b - a));
      if (i == 0 || i == q) d.setZero();
      ce.delta.push_back(d);
      st.max_sagitta = std::max(st.max_sagitta, d.norm());
      if (i > 0 && i < q)
        st.max_distance = std::max(st.max_distance, (g.closest_point(curves[e.group], pts[i]) - pts[i]).norm());
    }
    ce.lo = a.cwiseMin(b).array() - len;
    ce.hi = a.cwiseMax(b).array() + len;
    edges.push_back(std::move(ce));
    on_curve[directed_edge_key(e.v[0], e.v[1])] = pts;
    ++st.boundary_edges;
  }

  std::vector<double> l(q + 1), dl(q + 1);
  auto blend = [&](const Vec2& x) {
    Vec2 D(0, 0);
    double W = 0;
    for (const auto& e : edges) {
      if ((x.array() < e.lo.array()).any() || (x.array() > e.hi.array()).any()) continue;
      const Vec2 ab = e.b - e.a;
      const double s = std::clamp((x - e.a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
      const double w = wendland_c2((x - (e.a + s * ab)).norm() / e.rho);
      if (w == 0) continue;
      equispaced_lagrange(q, 2 * s - 1, l.data(), dl.data());
      Vec2 d(0, 0);
      for (int i = 0; i <= q; ++i) d += l[i] * e.delta[i];
      D += w * d;
      W += w;
    }
    return W > 1 ? Vec2(D / W) : D;
  };

  std::vector<char> on_boundary(m.nodes.size(), 0);
  for (const auto& e : m.boundary) on_boundary[e.v[0]] = on_boundary[e.v[1]] = 1;
  auto build = [&](bool global) {
    // interior vertices first (the corners of the control grids)
    std::vector<Vec2> nodes = m.nodes;
    for (size_t v = 0; v < nodes.size(); ++v)
      if (!on_boundary[v]) {
        Vec2 D = global ? blend(m.nodes[v]) : Vec2(0, 0);
        st.max_blend = std::max(st.max_blend, D.norm());
        nodes[v] += D;
      }

    const int n1 = q + 1;
    std::vector<Vec2> P(static_cast<size_t>(m.num_cells()) * n1 * n1);
    for (int c = 0; c < m.num_cells(); ++c) {
      const Cell& cell = m.cells[c];
      Vec2* X = P.data() + static_cast<size_t>(c) * n1 * n1;
      Vec2 V[4];
      for (int k = 0; k < 4; ++k) V[k] = m.nodes[cell.v[k]];  // straight positions
      // interior: bilinear map of the straight cell, then the blend
      for (int j = 1; j < q; ++j)
        for (int i = 1; i < q; ++i) {
          const double xi = -1 + 2.0 * i / q, eta = -1 + 2.0 * j / q;
          Vec2 x = 0.25 * ((1 - xi) * (1 - eta) * V[0] + (1 + xi) * (1 - eta) * V[1] + (1 + xi) * (1 + eta) * V[2] +
                           (1 - xi) * (1 + eta) * V[3]);
          Vec2 D = global ? blend(x) : Vec2(0, 0);
          if (global) st.max_blend = std::max(st.max_blend, D.norm());
          X[i + n1 * j] = x + D;
        }
      for (int e = 0; e < 4; ++e) {
        const int A = cell.v[e], B = cell.v[(e + 1) % 4];
        const std::vector<int> idx = edge_control_points(q, e);
        auto it = on_curve.find(directed_edge_key(A, B));
        auto rit = on_curve.find(directed_edge_key(B, A));
        for (int k = 0; k <= q; ++k) {
          Vec2 x;
          if (k == 0)
            x = nodes[A];
          else if (k == q)
            x = nodes[B];
          else if (it != on_curve.end())
            x = it->second[k];
          else if (rit != on_curve.end())
            x = rit->second[q - k];
          else {  // canonical direction (lower node id first): neighbours
                  // compute the same point
            const bool fwd = A < B;
            const Vec2 a = m.nodes[fwd ? A : B], b = m.nodes[fwd ? B : A];
            const double s = static_cast<double>(fwd ? k : q - k) / q;
            Vec2 y = a + s * (b - a);
            Vec2 D = global ? blend(y) : Vec2(0, 0);
            if (global) st.max_blend = std::max(st.max_blend, D.norm());
            x = y + D;
          }
          X[idx[k]] = x;
        }
      }
      if (!global) {  // transfinite (Coons) blend of the cell's own edge
                      // displacements
        Vec2 E[4][kMaxGeometricOrder + 1];
        for (int e = 0; e < 4; ++e) {
          const std::vector<int> idx = edge_control_points(q, e);
          const Vec2 a = V[e], b = V[(e + 1) % 4];
          for (int k = 0; k <= q; ++k) E[e][k] = X[idx[k]] - (a + (static_cast<double>(k) / q) * (b - a));
        }
        for (int j = 1; j < q; ++j)
          for (int i = 1; i < q; ++i) {
            const double xi = -1 + 2.0 * i / q, eta = -1 + 2.0 * j / q;
            X[i + n1 * j] +=
                0.5 * ((1 - eta) * E[0][i] + (1 + xi) * E[1][j] + (1 + eta) * E[2][q - i] + (1 - xi) * E[3][q - j]);
          }
      }
    }
    Mesh r = m;
    r.nodes = nodes;
    r.curved.order = q;
    r.curved.points = std::move(P);
    return r;
  };
  // the cells' own transfinite blend when it folds nothing, else the smooth blend across cells;
  // with `fallback`, a cell that still folds gets its boundary edges straight, until none folds
  Mesh best;
  ScaledJacobian sj;
  for (int attempt = 0;; ++attempt) {
    sj = ScaledJacobian{};
    for (bool global : {false, true}) {
      if (global && st.hanging) break;  // the smooth blend would bend the coarse edges of hanging nodes
      Mesh r = build(global);
      const ScaledJacobian s2 = min_scaled_jacobian(r);
      if (global && s2.min <= sj.min) continue;
      best = std::move(r);
      sj = s2;
      st.blend = global ? "smooth" : "transfinite";
      if (sj.min > 0) break;
    }
    if (sj.min > 0 || !fallback || attempt >= 1000) break;
    const Cell& bad = m.cells[sj.cell];
    int erased = 0;
    for (int e = 0; e < 4; ++e) {
      const int A = bad.v[e], B = bad.v[(e + 1) % 4];
      erased += static_cast<int>(on_curve.erase(directed_edge_key(A, B)) + on_curve.erase(directed_edge_key(B, A)));
    }
    if (erased == 0) break;  // folds without a curved edge: nothing to fall back to
    st.straight_edges += erased;
  }
  m = std::move(best);
  st.min_scaled_jacobian = sj.min;
  st.worst_cell = sj.cell;
  if (sj.min <= 0)
    throw NumericalError(path + ": curving the boundary cells folds " + cell_label(m, sj.cell) +
                         " (minimum scaled Jacobian " + sci(sj.min) +
                         "): the cell is too coarse along the curve; refine "
                         "there or lower --order");
  return st;
}

}  // namespace quadapt
