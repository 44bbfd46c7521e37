#pragma once
// 1D quadrature rules and the tensor-product Lagrange basis on Gauss-Lobatto (GLL) points that
// defines quadapt's DG field (thesis section 2.1; docs/design.md §3-4).
//
// Reference interval [-1, 1]; reference quad [-1,1]^2. A degree-p DG function on a quad has
// (p+1)^2 coefficients u_{i + (p+1) j}, the values at the GLL points (x_i, x_j):
//     u(xi, eta) = sum_{i,j} u_{i+(p+1)j} l_i(xi) l_j(eta),
// with l_i the degree-p Lagrange polynomial through the p+1 GLL points.
#include <Eigen/Core>
#include <vector>

namespace quadapt {

/// A 1D quadrature rule on [-1, 1].
struct Rule1D {
  std::vector<double> x;  ///< points, increasing
  std::vector<double> w;  ///< weights (sum 2)
};

/// n-point Gauss-Legendre rule (exact for degree 2n-1), n >= 1. Points to ~1e-15.
Rule1D gauss_legendre(int n);
/// n-point Gauss-Lobatto rule (includes -1 and 1; exact for degree 2n-3), n >= 2.
Rule1D gauss_lobatto(int n);

/// 1D Lagrange basis of degree p on the p+1 GLL points.
class LagrangeBasis1D {
 public:
  explicit LagrangeBasis1D(int p);
  int degree() const { return p_; }
  int size() const { return p_ + 1; }
  const std::vector<double>& nodes() const { return nodes_; }
  /// Values l_i(x), i = 0..p (size p+1).
  Eigen::VectorXd eval(double x) const;
  /// Derivatives l_i'(x), i = 0..p.
  Eigen::VectorXd deriv(double x) const;

 private:
  int p_;
  std::vector<double> nodes_;
  std::vector<double> bary_;  ///< barycentric weights
};

/// Evaluates a degree-p tensor-product DG function with coefficients `u` ((p+1)^2, index
/// i + (p+1) j) at reference point (xi, eta).
double eval_tensor(const LagrangeBasis1D& b, const double* u, double xi, double eta);

}  // namespace quadapt
