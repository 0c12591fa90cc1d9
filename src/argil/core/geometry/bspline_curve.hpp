#pragma once
// The B-spline / NURBS curve value type: control points of any dimension
// (2 for trim curves in a surface's (u, v) space, 4 for homogeneous rows).

#include <Eigen/Core>

#include "argil/core/geometry/bspline_surface.hpp"

namespace argil {

/// C(t) = sum_i N_i,p(t) w_i P_i / sum_i N_i,p(t) w_i, rational when `weights`
/// is non-empty.
/// - `degree` >= 1, `knots` clamped and non-decreasing, interior multiplicity
///   at most the degree (the rules of validate_knots()).
/// - `points` has count() = knots.size() - degree - 1 rows, one per control
///   point, of any dimension.
/// - `weights` is empty (polynomial) or has count() positive entries.
/// A plain value; call validate() before trusting data from outside.
struct BSplineCurve {
  using Points = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

  int degree = 1;
  Eigen::VectorXd knots;
  Points points;
  Eigen::VectorXd weights;  // empty: polynomial

  bool is_rational() const { return weights.size() > 0; }
  /// Number of control points (from the knot count).
  int count() const { return static_cast<int>(knots.size()) - degree - 1; }
  double domain_start() const { return knots[degree]; }
  double domain_end() const { return knots[count()]; }
};

/// Checks the knots (validate_knots(), fields "degree" and "knots"), then
/// points (count() rows, finite) and weights (empty or count(), finite and
/// positive, in the range surfaces allow). Point coordinates have no magnitude limit: curves carry
/// parameters, whose range the knots of the surface bound. The message names
/// the first problem's field, index and value.
Status validate(const BSplineCurve& curve);

/// Point of the curve at t, clamped to the domain. Precondition:
/// validate(curve).ok(). The NURBS Book A4.1.
Eigen::VectorXd evaluate(const BSplineCurve& curve, double t);

}  // namespace argil
