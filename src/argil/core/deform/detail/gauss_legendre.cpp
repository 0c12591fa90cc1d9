#include "argil/core/deform/detail/gauss_legendre.hpp"

#include <Eigen/Eigenvalues>
#include <cassert>
#include <cmath>

namespace argil::detail {

QuadratureRule gauss_legendre(int n) {
  assert(n >= 1 && n <= 64);
  // Symmetric tridiagonal Jacobi matrix of the Legendre polynomials on [-1, 1].
  Eigen::MatrixXd jacobi = Eigen::MatrixXd::Zero(n, n);
  for (int k = 1; k < n; ++k) {
    const double b = k / std::sqrt(4.0 * k * k - 1.0);
    jacobi(k, k - 1) = b;
    jacobi(k - 1, k) = b;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(jacobi);
  QuadratureRule rule;
  rule.points = 0.5 * (eigen.eigenvalues().array() + 1.0);
  // Weight on [-1, 1] is 2 v_0^2; mapped to [0, 1] it halves.
  rule.weights = eigen.eigenvectors().row(0).transpose().array().square();
  return rule;
}

}  // namespace argil::detail
