#include "lpcvt/cross_field.hpp"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <cmath>
#include <complex>

#include "core/error.hpp"
#include "frame/frame.hpp"
#include "mesh/topology.hpp"

namespace quadapt::lpcvt {

namespace {

constexpr double kPi = 3.14159265358979323846;

/// sigma_max / sigma_min of M (sqrt of the eigenvalue ratio of M^T M).
double stretch_of(const Mat2& M) {
  const double f = M.squaredNorm(), d = std::abs(M.determinant());
  if (!(d > 0)) return INFINITY;
  const double r = f / d;  // s + 1/s
  return 0.5 * (r + std::sqrt(std::max(0.0, r * r - 4)));
}

/// Angle of the lattice's first axis M^-1 e_1 (M without reflection: det > 0).
double lattice_angle(const Mat2& M) { return std::atan2(-M(1, 0), M(1, 1)); }

/// x wrapped to [-pi/4, pi/4).
double wrap_quarter(double x) {
  const double q = kPi / 2;
  return x - q * std::floor((x + q / 2) / q);
}

}  // namespace

double orientation_freedom(double s, const CrossFieldOptions& o) {
  if (!(s > o.free_below)) return 1;
  if (!(s < o.fixed_above)) return 0;
  const double t = std::log(s / o.free_below) / std::log(o.fixed_above / o.free_below);
  return 1 - t * t * (3 - 2 * t);
}

CrossFieldReport align_free_orientation(Background& bg, const CrossFieldOptions& o) {
  if (!(o.free_below >= 1 && o.fixed_above > o.free_below && o.kappa > 0))
    throw InputError("", "cross field: need 1 <= free_below < fixed_above and kappa > 0");
  CrossFieldReport rep;
  if (bg.is_analytic()) return rep;  // the analytic metrics state their own orientation
  const Mesh& mesh = bg.mesh();
  const int n = mesh.num_cells();
  std::vector<Mat2> M(n);
  std::vector<double> w(n), theta(n);  // freedom, lattice angle (reflection removed)
  for (int c = 0; c < n; ++c) {
    M[c] = bg.mesh_cell_metric(c);
    w[c] = orientation_freedom(stretch_of(M[c]), o);
    theta[c] = lattice_angle(without_reflection(M[c]));
    if (w[c] > 0) ++rep.free_cells;
  }
  if (rep.free_cells == 0) return rep;

  using Cplx = std::complex<double>;
  const auto cross = [](double angle) { return std::polar(1.0, 4 * angle); };
  std::vector<Eigen::Triplet<double>> trip;
  Eigen::VectorXd bre = Eigen::VectorXd::Zero(n), bim = Eigen::VectorXd::Zero(n);
  std::vector<double> diag(n, 0.0);
  for (int c = 0; c < n; ++c) {
    const double a = o.kappa * std::pow(1 - w[c], 4);
    if (a > 0) {
      const Cplx f = a * cross(theta[c]);
      diag[c] += a;
      bre[c] += f.real();
      bim[c] += f.imag();
    }
  }
  const Topology topo = build_topology(mesh);
  for (const Face& f : topo.faces) {
    const int i = f.cell[0], j = f.cell[1];
    if (j < 0) {
      const Vec2 t = f.b - f.a;
      const Cplx g = cross(std::atan2(t.y(), t.x()));
      diag[i] += 1;
      bre[i] += g.real();
      bim[i] += g.imag();
    } else {
      diag[i] += 1;
      diag[j] += 1;
      trip.emplace_back(i, j, -1.0);
      trip.emplace_back(j, i, -1.0);
    }
  }
  for (int c = 0; c < n; ++c) trip.emplace_back(c, c, diag[c]);
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(trip.begin(), trip.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(A);
  // every face-connected component has a wall face, so A is positive definite; a failed
  // factorisation means non-finite input
  if (ldlt.info() != Eigen::Success) throw NumericalError("cross field: the factorisation failed (non-finite frame?)");
  const Eigen::VectorXd ure = ldlt.solve(bre), uim = ldlt.solve(bim);

  double sum = 0;
  for (int c = 0; c < n; ++c) {
    if (w[c] <= 0) continue;
    const double phi = std::atan2(uim[c], ure[c]) / 4;
    const double d = w[c] * wrap_quarter(phi - theta[c]);
    if (d == 0) continue;
    const double cs = std::cos(d), sn = std::sin(d);
    Mat2 L;
    L << cs, sn, -sn, cs;  // R(-d): the lattice axis M^-1 e_1 turns by +d (exactly when M is conformal)
    M[c] = L * without_reflection(M[c]);
    ++rep.rotated_cells;
    sum += std::abs(d);
    rep.max_rotation_deg = std::max(rep.max_rotation_deg, std::abs(d) * 180 / kPi);
  }
  if (rep.rotated_cells > 0) {
    rep.mean_rotation_deg = sum / rep.rotated_cells * 180 / kPi;
    bg.set_mesh_cell_metrics(M);
  }
  return rep;
}

}  // namespace quadapt::lpcvt
