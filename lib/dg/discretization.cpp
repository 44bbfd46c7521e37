#include "dg/discretization.hpp"
#include "dg/degree.hpp"

#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>

#include "core/error.hpp"
#include "core/format.hpp"
#include "mesh/label.hpp"
#include "mesh/curved.hpp"

namespace quadapt {

namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

/// Values l[i] and derivatives dl[i] of the Lagrange polynomials through `nodes` at x.
void lagrange_1d(const std::vector<double>& nodes, double x, double* l, double* dl) {
  const int n = static_cast<int>(nodes.size());
  for (int i = 0; i < n; ++i) {
    double v = 1, d = 0;
    for (int m = 0; m < n; ++m) {
      if (m == i) continue;
      double g = 1.0 / (nodes[i] - nodes[m]);
      double f = (x - nodes[m]) * g;
      d = d * f + v * g;
      v *= f;
    }
    l[i] = v;
    dl[i] = d;
  }
}

/// The cell map: bilinear x(xi, eta) = a0 + a1 xi + a2 eta + a3 xi eta for a straight-sided
/// quad, the Lagrange map of mesh/curved.hpp for a curved one.
struct QuadGeo {
  Vec2 a0, a1, a2, a3;
  std::optional<CellMap> curved;
  explicit QuadGeo(const Mesh& m, int c) {
    if (m.is_curved()) curved.emplace(m, c);
    const Cell& cell = m.cells[c];
    const Vec2 &X0 = m.nodes[cell.v[0]], &X1 = m.nodes[cell.v[1]], &X2 = m.nodes[cell.v[2]],
               &X3 = m.nodes[cell.v[3]];
    a0 = 0.25 * (X0 + X1 + X2 + X3);
    a1 = 0.25 * (-X0 + X1 + X2 - X3);
    a2 = 0.25 * (-X0 - X1 + X2 + X3);
    a3 = 0.25 * (X0 - X1 + X2 - X3);
  }
  Vec2 map(double xi, double eta) const {
    if (curved) return curved->map(xi, eta);
    return a0 + a1 * xi + a2 * eta + a3 * (xi * eta);
  }
  /// Columns of the Jacobian: t1 = dx/dxi, t2 = dx/deta; returns det.
  double jac(double xi, double eta, Vec2& t1, Vec2& t2) const {
    if (curved) return curved->jacobian(xi, eta, t1, t2);
    t1 = a1 + a3 * eta;
    t2 = a2 + a3 * xi;
    return t1.x() * t2.y() - t1.y() * t2.x();
  }
};

/// Geometry of face f at parameter t in [0, 1] (from a to b), on side 0's map G: the point x,
/// side 0's outward unit normal n and the arc length per unit t. Straight faces: the segment.
void face_geometry(const QuadGeo& G, const Face& f, double t, Vec2& x, Vec2& n, double& dsdt) {
  if (!G.curved) {
    x = f.a + t * (f.b - f.a);
    n = f.normal;
    dsdt = f.length;
    return;
  }
  dsdt = edge_geometry(*G.curved, f.local_edge[0], f.s_a[0] + t * (f.s_b[0] - f.s_a[0]), x, n) * (f.s_b[0] - f.s_a[0]);
}

}  // namespace

// ============================================================================ Impl

struct DGDiscretization::Impl {
  int p = 1, n1 = 2, nb = 4;
  std::vector<double> gll;     // GLL nodes
  Rule1D gv;                   // volume / face Gauss rule
  int nq = 0, Q = 0;
  MatrixXd V, Gxi, Geta;       // Q x nb reference tables (q = q1 + nq q2)
  std::vector<QuadGeo> geo;
  std::vector<double> area;
  std::vector<std::array<double, 4>> height;  // |K| / |edge e| (arc length when curved)
  // Face geometry at the nf face Gauss points of side 0 (index f * nf + q): physical point x,
  // unit normal n (side 0 outward) and arc-length weight w (including the Gauss weight).
  // Straight faces: x on the segment [a, b], n = Face::normal, w = w_q |b - a| / 2.
  std::vector<Vec2> fx, fn;
  std::vector<double> fw;
  // Boundary data per group: index into data programs (-1: the exact solution's trace / flux).
  std::vector<int> group_dirichlet, group_neumann;
  std::vector<ExprProgram> data;
  std::vector<std::vector<int>> rows;         // block pattern: sorted row cells of column cell c
  std::vector<long long> col_start;           // first nnz of cell c's block column
  long long nnz = 0;
};

DGDiscretization::DGDiscretization(const Mesh& mesh, const Case& cs, int p, const DGOptions& opt)
    : mesh_(mesh), cs_(cs), p_(p), nb_((p + 1) * (p + 1)), opt_(opt) {
  check_degree(p, "degree p =");
  if (mesh.num_cells() == 0) throw InputError("mesh: no cells");
  if (!mesh.all_quads())
    throw InputError("mesh: " + std::to_string(mesh.num_triangles()) +
                     " triangles; the DG solver needs an all-quad mesh (use recombine)");
  // the case's boundary names against the mesh's groups (the tools check this first, with the
  // file names; here for every caller of the library)
  check_case_boundaries(cs, mesh);
  // the options as the header states them, for every caller of the library (a negative penalty
  // solved to a 15x larger error and extra_points < 1 was raised to 1 unseen: a library user's
  // review, session 38; dgsolve --penalty refused it already)
  if (!(opt_.penalty_factor > 0) || !std::isfinite(opt_.penalty_factor))
    throw InputError("DGOptions::penalty_factor = " + std::to_string(opt_.penalty_factor) +
                     ": the SIPG penalty factor must be a positive number (dgsolve --penalty)");
  if (!(opt_.boundary_penalty_factor < 0 || opt_.boundary_penalty_factor > 0) ||
      !std::isfinite(opt_.boundary_penalty_factor))
    throw InputError("DGOptions::boundary_penalty_factor = " + std::to_string(opt_.boundary_penalty_factor) +
                     ": positive, or negative for penalty_factor's");
  if (opt_.extra_points < 1)
    throw InputError("DGOptions::extra_points = " + std::to_string(opt_.extra_points) + ": at least 1");
  if (opt_.error_points < 0)
    throw InputError("DGOptions::error_points = " + std::to_string(opt_.error_points) + ": 0 (automatic) or more");
  topo_ = build_topology(mesh);
  exact_ = std::make_unique<ExactSolution>(cs);
  impl_ = std::make_unique<Impl>();
  Impl& I = *impl_;
  I.p = p;
  I.n1 = p + 1;
  I.nb = nb_;
  LagrangeBasis1D basis(p);
  I.gll = basis.nodes();
  I.nq = p + 1 + opt_.extra_points;
  I.gv = gauss_legendre(I.nq);
  I.Q = I.nq * I.nq;
  I.V.resize(I.Q, nb_);
  I.Gxi.resize(I.Q, nb_);
  I.Geta.resize(I.Q, nb_);
  {
    std::vector<std::vector<double>> l(I.nq, std::vector<double>(I.n1)), dl = l;
    for (int q = 0; q < I.nq; ++q) lagrange_1d(I.gll, I.gv.x[q], l[q].data(), dl[q].data());
    for (int q2 = 0; q2 < I.nq; ++q2)
      for (int q1 = 0; q1 < I.nq; ++q1)
        for (int j = 0; j < I.n1; ++j)
          for (int i = 0; i < I.n1; ++i) {
            int q = q1 + I.nq * q2, a = i + I.n1 * j;
            I.V(q, a) = l[q1][i] * l[q2][j];
            I.Gxi(q, a) = dl[q1][i] * l[q2][j];
            I.Geta(q, a) = l[q1][i] * dl[q2][j];
          }
  }
  const int nc = mesh.num_cells();
  I.geo.reserve(nc);
  I.area.resize(nc);
  I.height.resize(nc);
  for (int c = 0; c < nc; ++c) {
    I.geo.emplace_back(mesh, c);
    double a = 0;
    for (int q2 = 0; q2 < I.nq; ++q2)
      for (int q1 = 0; q1 < I.nq; ++q1) {
        Vec2 t1, t2;
        double det = I.geo[c].jac(I.gv.x[q1], I.gv.x[q2], t1, t2);
        if (!(det > 0)) {
          Vec2 ctr = I.geo[c].a0;
          throw InputError("mesh: cell " + number_text(c) + " near " + point_text(ctr) +
                           " is inverted or degenerate (Jacobian " + sci(det) + ")");
        }
        a += I.gv.w[q1] * I.gv.w[q2] * det;
      }
    I.area[c] = a;
    const Cell& cell = mesh.cells[c];
    for (int e = 0; e < 4; ++e) {
      double len = 0;
      if (mesh.is_curved()) {
        for (int q = 0; q < I.nq; ++q) {
          Vec2 x, n;
          len += 0.5 * I.gv.w[q] * edge_geometry(*I.geo[c].curved, e, 0.5 * (I.gv.x[q] + 1), x, n);
        }
      } else {
        len = (mesh.nodes[cell.v[(e + 1) % 4]] - mesh.nodes[cell.v[e]]).norm();
      }
      I.height[c][e] = a / len;
    }
  }

  // Face geometry at the face Gauss points.
  const size_t nfq = static_cast<size_t>(I.nq);
  I.fx.resize(topo_.faces.size() * nfq);
  I.fn.resize(I.fx.size());
  I.fw.resize(I.fx.size());
  for (size_t fi = 0; fi < topo_.faces.size(); ++fi) {
    const Face& f = topo_.faces[fi];
    for (size_t q = 0; q < nfq; ++q) {
      const size_t k = fi * nfq + q;
      double dsdt;
      const double t = 0.5 * (I.gv.x[q] + 1);
      face_geometry(I.geo[f.cell[0]], f, t, I.fx[k], I.fn[k], dsdt);
      I.fw[k] = 0.5 * I.gv.w[q] * dsdt;
      if (mesh.is_curved() && !f.is_boundary()) {
        // Both sides must trace the same curve (shared edge nodes; at a hanging node the coarse
        // edge's part [s_a, s_b] and the fine edge): the traces are matched by the edge parameter.
        double xi, eta;
        edge_reference_point(f.local_edge[1], f.s_a[1] + t * (f.s_b[1] - f.s_a[1]), xi, eta);
        const Vec2 x1 = I.geo[f.cell[1]].map(xi, eta);
        if ((x1 - I.fx[k]).norm() > 1e-9 * f.length)
          throw InputError("mesh: cells " + std::to_string(f.cell[0] + 1) + " and " + std::to_string(f.cell[1] + 1) +
                           " share the edge near (" + std::to_string(I.fx[k].x()) + ", " + std::to_string(I.fx[k].y()) +
                           ") but their curved edges differ by " + std::to_string((x1 - I.fx[k]).norm()) +
                           " (the edge's high-order nodes must be shared)");
      }
    }
  }

  // Boundary conditions per face.
  face_dirichlet_.assign(topo_.faces.size(), 0);
  for (size_t fi = 0; fi < topo_.faces.size(); ++fi) {
    const Face& f = topo_.faces[fi];
    if (!f.is_boundary()) continue;
    std::string name = f.group >= 0 ? mesh.groups[f.group].name : std::string();
    face_dirichlet_[fi] = cs.is_dirichlet(name) ? 1 : 0;
  }
  // Boundary data given as expressions (case file's map forms).
  const int ng = static_cast<int>(mesh.groups.size());
  I.group_dirichlet.assign(ng, -1);
  I.group_neumann.assign(ng, -1);
  for (int gi = 0; gi < ng; ++gi) {
    if (const BoundaryData* d = cs.dirichlet_value(mesh.groups[gi].name)) {
      I.group_dirichlet[gi] = static_cast<int>(I.data.size());
      I.data.emplace_back(std::vector<Expr>{d->expr});
    }
    if (const BoundaryData* d = cs.neumann_value(mesh.groups[gi].name)) {
      I.group_neumann[gi] = static_cast<int>(I.data.size());
      I.data.emplace_back(std::vector<Expr>{d->expr});
    }
  }
  if (cs.has_functional()) {
    // every group of that name (a file may give two groups one name; Dirichlet data above
    // match by name too)
    functional_groups_.assign(ng, 0);
    for (int gi = 0; gi < ng; ++gi)
      if (mesh.groups[gi].name == cs.functional_boundary) functional_groups_[gi] = 1, has_functional_ = true;
  }

  // Block pattern and column offsets.
  I.rows.resize(nc);
  for (int c = 0; c < nc; ++c) {
    std::vector<int>& r = I.rows[c];
    r.push_back(c);
    for (int fi : topo_.cell_faces[c]) {
      const Face& f = topo_.faces[fi];
      if (f.is_boundary()) continue;
      r.push_back(f.cell[0] == c ? f.cell[1] : f.cell[0]);
    }
    std::sort(r.begin(), r.end());
    r.erase(std::unique(r.begin(), r.end()), r.end());
  }
  I.col_start.resize(nc + 1);
  I.col_start[0] = 0;
  for (int c = 0; c < nc; ++c)
    I.col_start[c + 1] = I.col_start[c] + static_cast<long long>(nb_) * nb_ * I.rows[c].size();
  I.nnz = I.col_start[nc];
  if (I.nnz > 2000000000LL) throw InputError("problem too large for 32-bit sparse indices");
}

DGDiscretization::~DGDiscretization() = default;

// ============================================================================ assembly

void DGDiscretization::assemble(SparseMatrixCSC& A, Eigen::VectorXd& b) const {
  const Impl& I = *impl_;
  const int N = num_dofs(), nb = nb_;
  A.resize(N, N);
  A.resizeNonZeros(static_cast<Eigen::Index>(I.nnz));
  int* outer = A.outerIndexPtr();
  int* inner = A.innerIndexPtr();
  double* val = A.valuePtr();
  outer[N] = static_cast<int>(I.nnz);
  assemble_columns(
      [&](int c, const std::vector<MatrixXd>& blk) {
        const std::vector<int>& rows = I.rows[c];
        const int nr = static_cast<int>(rows.size());
        const long long len = static_cast<long long>(nr) * nb;
        for (int bcol = 0; bcol < nb; ++bcol) {
          long long base = I.col_start[c] + bcol * len;
          outer[c * nb + bcol] = static_cast<int>(base);
          for (int k = 0; k < nr; ++k) {
            const int r0 = rows[k] * nb;
            const double* src = blk[k].data() + static_cast<long long>(bcol) * nb;
            for (int a = 0; a < nb; ++a) {
              inner[base + k * nb + a] = r0 + a;
              val[base + k * nb + a] = src[a];
            }
          }
        }
      },
      b);
}

void DGDiscretization::assemble(BlockSparseMatrix& A, Eigen::VectorXd& b) const {
  const Impl& I = *impl_;
  const int nc = mesh_.num_cells(), nb = nb_;
  // The pattern is symmetric: block row r holds the cells of rows[r].
  std::vector<long long> rs(nc + 1, 0);
  for (int c = 0; c < nc; ++c) rs[c + 1] = rs[c] + static_cast<long long>(I.rows[c].size());
  std::vector<int> cols;
  cols.reserve(rs[nc]);
  for (int c = 0; c < nc; ++c) cols.insert(cols.end(), I.rows[c].begin(), I.rows[c].end());
  A = BlockSparseMatrix(nb, std::move(rs), std::move(cols));
  const size_t bs = static_cast<size_t>(nb) * nb;
  assemble_columns(
      [&](int c, const std::vector<MatrixXd>& blk) {
        const std::vector<int>& rows = I.rows[c];
        for (size_t k = 0; k < rows.size(); ++k) {
          long long pos = A.find(rows[k], c);
          std::copy(blk[k].data(), blk[k].data() + bs, A.block(pos));
        }
      },
      b);
}

void DGDiscretization::assemble_columns(
    const std::function<void(int, const std::vector<Eigen::MatrixXd>&)>& scatter, Eigen::VectorXd& b) const {
  const Impl& I = *impl_;
  const int nc = mesh_.num_cells(), nb = nb_, n1 = I.n1, nq = I.nq, Q = I.Q;
  b.setZero(num_dofs());

  const Eigen::Matrix2d D = cs_.diffusion;
  const Vec2 cvec = cs_.advection;
  const bool diff = !cs_.advection_only();
  const bool adv = !cvec.isZero(0.0);
  const double pen_base = opt_.penalty_factor * p_ * (p_ + 1);
  const double pen_base_boundary =
      (opt_.boundary_penalty_factor < 0 ? opt_.penalty_factor : opt_.boundary_penalty_factor) * p_ * (p_ + 1);
  const int nf = nq;  // face Gauss points
  const Rule1D& g = I.gv;

#pragma omp parallel
  {
    const int kvol = (diff ? 2 : 0) + (adv ? 1 : 0);
    MatrixXd Dx(Q, nb), Dy(Q, nb), L(kvol * Q, nb), R(kvol * Q, nb);
    VectorXd W(Q), f(Q), rhs(nb);
    std::vector<MatrixXd> blk;
    MatrixXd Phi[2], Nn[2], FL(2 * nf, nb), FR(2 * nf, nb), B(nb, nb);
    for (int k = 0; k < 2; ++k) {
      Phi[k].resize(nf, nb);
      Nn[k].resize(nf, nb);
    }
    VectorXd Wf(nf), gD(nf), gN(nf), nDn(nf), cn(nf), cplus(nf), cminus(nf), pen(nf), alpha(nf);
    std::vector<Vec2> Dn(nf);
    int nscratch = exact_->scratch_size();
    for (const ExprProgram& d : I.data) nscratch = std::max(nscratch, d.scratch_size());
    std::vector<double> scratch(nscratch);
    std::vector<double> lx(n1), dlx(n1), ly(n1), dly(n1);
    double ex[ExactSolution::NUM_OUTPUTS];

    // Trace of side k of face f at the face Gauss points: values Phi[k] and normal fluxes
    // Nn[k](q) = (D grad phi) . n_q with n_q the side-0 normal at point q (Dn[q] = D n_q).
    auto trace = [&](const Face& fc, int k, const Vec2* Dn) {
      const int c = fc.cell[k], e = fc.local_edge[k];
      const QuadGeo& G = I.geo[c];
      for (int q = 0; q < nf; ++q) {
        double t = 0.5 * (g.x[q] + 1);
        double s = fc.s_a[k] + t * (fc.s_b[k] - fc.s_a[k]);
        double xi, eta;
        edge_reference_point(e, s, xi, eta);
        lagrange_1d(I.gll, xi, lx.data(), dlx.data());
        lagrange_1d(I.gll, eta, ly.data(), dly.data());
        if (diff) {
          Vec2 t1, t2;
          double det = G.jac(xi, eta, t1, t2);
          // grad phi = J^-T (dphi/dxi, dphi/deta); project on D n.
          double cxi = (t2.y() * Dn[q].x() - t2.x() * Dn[q].y()) / det;
          double ceta = (-t1.y() * Dn[q].x() + t1.x() * Dn[q].y()) / det;
          for (int j = 0; j < n1; ++j)
            for (int i = 0; i < n1; ++i) {
              int a = i + n1 * j;
              Phi[k](q, a) = lx[i] * ly[j];
              Nn[k](q, a) = cxi * dlx[i] * ly[j] + ceta * lx[i] * dly[j];
            }
        } else {
          for (int j = 0; j < n1; ++j)
            for (int i = 0; i < n1; ++i) Phi[k](q, i + n1 * j) = lx[i] * ly[j];
        }
      }
    };

#pragma omp for schedule(dynamic, 32)
    for (int c = 0; c < nc; ++c) {
      const std::vector<int>& rows = I.rows[c];
      const int nr = static_cast<int>(rows.size());
      if (static_cast<int>(blk.size()) < nr) blk.resize(nr);
      for (int k = 0; k < nr; ++k) blk[k].setZero(nb, nb);
      const int kd = static_cast<int>(std::lower_bound(rows.begin(), rows.end(), c) - rows.begin());
      auto pos = [&](int cell) {
        return static_cast<int>(std::lower_bound(rows.begin(), rows.end(), cell) - rows.begin());
      };

      // ---------------------------------------------------------------- volume
      const QuadGeo& G = I.geo[c];
      for (int q2 = 0; q2 < nq; ++q2)
        for (int q1 = 0; q1 < nq; ++q1) {
          const int q = q1 + nq * q2;
          Vec2 t1, t2;
          double det = G.jac(g.x[q1], g.x[q2], t1, t2);
          W[q] = g.w[q1] * g.w[q2] * det;
          Vec2 x = G.map(g.x[q1], g.x[q2]);
          exact_->eval(x.x(), x.y(), ex, scratch.data());
          f[q] = -ex[ExactSolution::S];
          double inv = 1.0 / det;
          double jxx = t2.y() * inv, jxe = -t1.y() * inv, jyx = -t2.x() * inv, jye = t1.x() * inv;
          Dx.row(q) = jxx * I.Gxi.row(q) + jxe * I.Geta.row(q);
          Dy.row(q) = jyx * I.Gxi.row(q) + jye * I.Geta.row(q);
        }
      {
        int off = 0;
        if (diff) {
          L.middleRows(0, Q) = Dx;
          L.middleRows(Q, Q) = Dy;
          R.middleRows(0, Q) = W.asDiagonal() * (D(0, 0) * Dx + D(0, 1) * Dy);
          R.middleRows(Q, Q) = W.asDiagonal() * (D(1, 0) * Dx + D(1, 1) * Dy);
          off = 2 * Q;
        }
        if (adv) {
          L.middleRows(off, Q) = cvec.x() * Dx + cvec.y() * Dy;
          R.middleRows(off, Q) = -(W.asDiagonal() * I.V);
        }
        blk[kd].noalias() += L.transpose() * R;
        rhs.noalias() = I.V.transpose() * W.cwiseProduct(f);
      }

      // ---------------------------------------------------------------- faces
      // Per face Gauss point q: normal n_q (side 0 outward), Dn_q = D n_q, n_q.D n_q, c.n_q.
      for (int fi : topo_.cell_faces[c]) {
        const Face& fc = topo_.faces[fi];
        const size_t f0 = static_cast<size_t>(fi) * nf;
        for (int q = 0; q < nf; ++q) {
          const Vec2& n = I.fn[f0 + q];
          Dn[q] = D * n;
          nDn[q] = n.dot(Dn[q]);
          cn[q] = cvec.dot(n);
          Wf[q] = I.fw[f0 + q];
        }
        if (fc.is_boundary()) {
          // c is side 0; n is outward.
          trace(fc, 0, Dn.data());
          const int gd = fc.group >= 0 ? I.group_dirichlet[fc.group] : -1;
          const int gn = fc.group >= 0 ? I.group_neumann[fc.group] : -1;
          for (int q = 0; q < nf; ++q) {
            const Vec2& x = I.fx[f0 + q];
            exact_->eval(x.x(), x.y(), ex, scratch.data());
            gD[q] = ex[ExactSolution::U];
            gN[q] = Dn[q].x() * ex[ExactSolution::UX] + Dn[q].y() * ex[ExactSolution::UY];
            if (gd >= 0 && face_dirichlet_[fi]) I.data[gd].eval(x.x(), x.y(), &gD[q], scratch.data());
            if (gn >= 0) I.data[gn].eval(x.x(), x.y(), &gN[q], scratch.data());
            cplus[q] = std::max(cn[q], 0.0);
            cminus[q] = std::min(cn[q], 0.0);
          }
          if (diff && face_dirichlet_[fi]) {
            const double hK = I.height[c][fc.local_edge[0]];
            for (int q = 0; q < nf; ++q) pen[q] = pen_base_boundary * nDn[q] / hK;
            FL.topRows(nf) = Phi[0];
            FL.bottomRows(nf) = Nn[0];
            FR.topRows(nf) = Wf.asDiagonal() * (-Nn[0] + (pen + cplus).asDiagonal() * Phi[0]);
            FR.bottomRows(nf) = -(Wf.asDiagonal() * Phi[0]);
            blk[kd].noalias() += FL.transpose() * FR;
            VectorXd wg = Wf.cwiseProduct(gD);
            rhs.noalias() += Phi[0].transpose() * (pen - cminus).cwiseProduct(wg) - Nn[0].transpose() * wg;
          } else {
            // Natural: Neumann data (the case's, else D grad u_exact . n), upwind advection with
            // outside state u_exact.
            if (cplus.maxCoeff() > 0) blk[kd].noalias() += Phi[0].transpose() * (Wf.cwiseProduct(cplus).asDiagonal() * Phi[0]);
            if (!diff) gN.setZero();
            VectorXd data = Wf.cwiseProduct(gN - cminus.cwiseProduct(gD));
            rhs.noalias() += Phi[0].transpose() * data;
          }
          continue;
        }
        const int j = fc.cell[0] == c ? 0 : 1;  // trial side (this cell)
        const int i = 1 - j;                    // the neighbour's side
        const int other = fc.cell[i];
        trace(fc, 0, Dn.data());
        trace(fc, 1, Dn.data());
        const double sgn[2] = {1.0, -1.0};
        const double h = std::min(I.height[fc.cell[0]][fc.local_edge[0]], I.height[fc.cell[1]][fc.local_edge[1]]);
        for (int q = 0; q < nf; ++q) pen[q] = diff ? pen_base * nDn[q] / h : 0.0;
        for (int ti : {j, i}) {  // test side
          // alpha_q = pen sgn_ti sgn_j + sgn_ti up_j c.n, up_j = 1 when side j is upwind at q.
          for (int q = 0; q < nf; ++q) {
            const double up = (cn[q] >= 0) == (j == 0) ? 1.0 : 0.0;
            alpha[q] = pen[q] * sgn[ti] * sgn[j] + sgn[ti] * up * cn[q];
          }
          if (diff) {
            FL.topRows(nf) = Phi[ti];
            FL.bottomRows(nf) = Nn[ti];
            FR.topRows(nf) = Wf.asDiagonal() * (-0.5 * sgn[ti] * Nn[j] + alpha.asDiagonal() * Phi[j]);
            FR.bottomRows(nf) = (-0.5 * sgn[j]) * (Wf.asDiagonal() * Phi[j]);
            B.noalias() = FL.transpose() * FR;
          } else {
            B.noalias() = Phi[ti].transpose() * (Wf.cwiseProduct(alpha).asDiagonal() * Phi[j]);
          }
          blk[ti == j ? kd : pos(other)] += B;
        }
      }

      // ---------------------------------------------------------------- scatter
      scatter(c, blk);
      b.segment(static_cast<long long>(c) * nb, nb) = rhs;
    }
  }
}

Eigen::VectorXd DGDiscretization::residual(const Eigen::VectorXd& U) const {
  SparseMatrixCSC A;
  VectorXd b;
  assemble(A, b);
  return A * U - b;
}

// ============================================================================ post-processing

std::vector<double> DGDiscretization::cell_l2_errors_squared(const Eigen::VectorXd& U) const {
  const Impl& I = *impl_;
  const int nc = mesh_.num_cells(), n1 = I.n1;
  const int ne = opt_.error_points > 0 ? opt_.error_points : std::max(2 * p_ + 4, 10);
  Rule1D ge = gauss_legendre(ne);
  MatrixXd T(ne, n1);
  {
    std::vector<double> l(n1), dl(n1);
    for (int q = 0; q < ne; ++q) {
      lagrange_1d(I.gll, ge.x[q], l.data(), dl.data());
      for (int i = 0; i < n1; ++i) T(q, i) = l[i];
    }
  }
  std::vector<double> err(nc);
#pragma omp parallel
  {
    std::vector<double> scratch(exact_->scratch_size());
    MatrixXd Uq(ne, ne);
#pragma omp for schedule(static)
    for (int c = 0; c < nc; ++c) {
      Eigen::Map<const MatrixXd> Uc(U.data() + static_cast<long long>(c) * nb_, n1, n1);
      Uq.noalias() = T * Uc * T.transpose();
      const QuadGeo& G = I.geo[c];
      double s = 0;
      for (int q2 = 0; q2 < ne; ++q2)
        for (int q1 = 0; q1 < ne; ++q1) {
          Vec2 t1, t2;
          double det = G.jac(ge.x[q1], ge.x[q2], t1, t2);
          Vec2 x = G.map(ge.x[q1], ge.x[q2]);
          double d = Uq(q1, q2) - exact_->eval_u(x.x(), x.y(), scratch.data());
          s += ge.w[q1] * ge.w[q2] * det * d * d;
        }
      err[c] = s;
    }
  }
  return err;
}

double DGDiscretization::l2_error(const Eigen::VectorXd& U) const {
  std::vector<double> e = cell_l2_errors_squared(U);
  double s = 0;
  for (double v : e) s += v;
  return std::sqrt(s);
}

double DGDiscretization::evaluate(const Eigen::VectorXd& U, int c, double xi, double eta) const {
  LagrangeBasis1D b(p_);
  return eval_tensor(b, U.data() + static_cast<long long>(c) * nb_, xi, eta);
}

namespace {
// Trace values of the degree-p basis of side 0 of boundary face f at Gauss point t in [0,1].
void boundary_trace(const Face& f, const std::vector<double>& gll, double t, double* phi) {
  const int n1 = static_cast<int>(gll.size());
  double s = f.s_a[0] + t * (f.s_b[0] - f.s_a[0]);
  double xi, eta;
  edge_reference_point(f.local_edge[0], s, xi, eta);
  std::vector<double> lx(n1), dlx(n1), ly(n1), dly(n1);
  lagrange_1d(gll, xi, lx.data(), dlx.data());
  lagrange_1d(gll, eta, ly.data(), dly.data());
  for (int j = 0; j < n1; ++j)
    for (int i = 0; i < n1; ++i) phi[i + n1 * j] = lx[i] * ly[j];
}
}  // namespace

double DGDiscretization::functional(const Eigen::VectorXd& U) const {
  if (!has_functional_) return 0;
  Rule1D g = gauss_legendre(p_ + 2);
  std::vector<double> phi(nb_);
  double J = 0;
  for (const Face& f : topo_.faces) {
    if (!on_functional_boundary(f)) continue;
    const double* Uc = U.data() + static_cast<long long>(f.cell[0]) * nb_;
    for (size_t q = 0; q < g.x.size(); ++q) {
      const double t = 0.5 * (g.x[q] + 1);
      boundary_trace(f, impl_->gll, t, phi.data());
      double u = 0;
      for (int a = 0; a < nb_; ++a) u += Uc[a] * phi[a];
      Vec2 x, n;
      double dsdt;
      face_geometry(impl_->geo[f.cell[0]], f, t, x, n, dsdt);
      J += 0.5 * g.w[q] * dsdt * u * u;
    }
  }
  return J;
}

Eigen::VectorXd DGDiscretization::functional_gradient(const Eigen::VectorXd& U) const {
  VectorXd dJ = VectorXd::Zero(num_dofs());
  if (!has_functional_) return dJ;
  Rule1D g = gauss_legendre(p_ + 2);
  std::vector<double> phi(nb_);
  for (const Face& f : topo_.faces) {
    if (!on_functional_boundary(f)) continue;
    const long long off = static_cast<long long>(f.cell[0]) * nb_;
    for (size_t q = 0; q < g.x.size(); ++q) {
      const double t = 0.5 * (g.x[q] + 1);
      boundary_trace(f, impl_->gll, t, phi.data());
      double u = 0;
      for (int a = 0; a < nb_; ++a) u += U[off + a] * phi[a];
      Vec2 x, n;
      double dsdt;
      face_geometry(impl_->geo[f.cell[0]], f, t, x, n, dsdt);
      double w = 0.5 * g.w[q] * dsdt;
      for (int a = 0; a < nb_; ++a) dJ[off + a] += 2 * w * u * phi[a];
    }
  }
  return dJ;
}

double DGDiscretization::functional_exact() const {
  if (!has_functional_) return 0;
  // Composite 20-point Gauss on 8 sub-intervals of every face.
  Rule1D g = gauss_legendre(20);
  const int sub = 8;
  double J = 0;
  for (const Face& f : topo_.faces) {
    if (!on_functional_boundary(f)) continue;
    for (int k = 0; k < sub; ++k)
      for (size_t q = 0; q < g.x.size(); ++q) {
        double t = (k + 0.5 * (g.x[q] + 1)) / sub;
        Vec2 x, n;
        double dsdt;
        face_geometry(impl_->geo[f.cell[0]], f, t, x, n, dsdt);
        double u = exact_->u(x.x(), x.y());
        J += 0.5 * g.w[q] * dsdt / sub * u * u;
      }
  }
  return J;
}

Eigen::VectorXd DGDiscretization::interpolate_exact() const {
  const Impl& I = *impl_;
  VectorXd U(num_dofs());
  const int nc = mesh_.num_cells(), n1 = I.n1;
#pragma omp parallel
  {
    std::vector<double> scratch(exact_->scratch_size());
#pragma omp for schedule(static)
    for (int c = 0; c < nc; ++c)
      for (int j = 0; j < n1; ++j)
        for (int i = 0; i < n1; ++i) {
          Vec2 x = I.geo[c].map(I.gll[i], I.gll[j]);
          U[static_cast<long long>(c) * nb_ + i + n1 * j] = exact_->eval_u(x.x(), x.y(), scratch.data());
        }
  }
  return U;
}

Eigen::VectorXd DGDiscretization::inject(const Eigen::VectorXd& U_from, int p_from) const {
  const int m1 = p_from + 1, n1 = p_ + 1, nc = mesh_.num_cells();
  if (U_from.size() != static_cast<Eigen::Index>(m1) * m1 * nc)
    throw InputError("inject: vector of size " + std::to_string(U_from.size()) + " does not match degree " +
                     std::to_string(p_from) + " on " + std::to_string(nc) + " cells");
  LagrangeBasis1D from(p_from);
  MatrixXd T(n1, m1);
  std::vector<double> l(m1), dl(m1);
  for (int k = 0; k < n1; ++k) {
    lagrange_1d(from.nodes(), impl_->gll[k], l.data(), dl.data());
    for (int i = 0; i < m1; ++i) T(k, i) = l[i];
  }
  VectorXd U(num_dofs());
  for (int c = 0; c < nc; ++c) {
    Eigen::Map<const MatrixXd> Uc(U_from.data() + static_cast<long long>(c) * m1 * m1, m1, m1);
    Eigen::Map<MatrixXd> Vc(U.data() + static_cast<long long>(c) * nb_, n1, n1);
    Vc.noalias() = T * Uc * T.transpose();
  }
  return U;
}

}  // namespace quadapt
