#pragma once
// Gauss-Legendre quadrature on [0, 1]: n points integrate polynomials of
// degree 2n - 1 exactly.

#include <Eigen/Core>

namespace argil::detail {

struct QuadratureRule {
  Eigen::VectorXd points;   // in (0, 1), increasing
  Eigen::VectorXd weights;  // positive, summing to 1
};

/// The n-point rule, 1 <= n <= 64 (Golub-Welsch: the eigenvalues of the
/// Jacobi matrix of the Legendre recurrence).
QuadratureRule gauss_legendre(int n);

}  // namespace argil::detail
