#pragma once
// Univariate B-spline and Bernstein basis functions (The NURBS Book, ch. 2).

#include <Eigen/Core>

namespace argil {

/// Knot span index s with knots[s] <= t < knots[s+1] for a clamped knot vector
/// with `count` control points; t at (or beyond) the end maps to the last
/// non-empty span, t before the start to the first. The NURBS Book A2.1.
int find_span(int degree, const Eigen::VectorXd& knots, int count, double t);

/// Multiplicity of knot value t in `knots` (exact comparison).
int knot_multiplicity(const Eigen::VectorXd& knots, double t);

/// Non-zero basis functions and their derivatives at t in span `span`:
/// `out(k, r)` = d^k/dt^k N_{span-degree+r, degree}(t), k = 0..order,
/// r = 0..degree. `out` is resized to (order+1) x (degree+1). Derivatives of
/// order above the degree are zero. The NURBS Book A2.3.
void basis_derivatives(int degree, const Eigen::VectorXd& knots, int span, double t, int order,
                       Eigen::Ref<Eigen::MatrixXd> out);

/// Convenience form that allocates.
Eigen::MatrixXd basis_derivatives(int degree, const Eigen::VectorXd& knots, int span, double t,
                                  int order);

/// Bernstein polynomials B_{i,degree}(t), i = 0..degree, t in [0, 1].
Eigen::VectorXd bernstein(int degree, double t);

}  // namespace argil
