#pragma once
// Knot insertion (The NURBS Book A5.1): refines the knot vector without
// changing the curve or surface.

#include <Eigen/Core>

#include "argil/core/geometry/bspline_surface.hpp"
#include "argil/core/base/status.hpp"

namespace argil {

/// A curve of any point dimension: `points` has one row per control point.
struct CurveNet {
  int degree = 1;
  Eigen::VectorXd knots;
  Eigen::MatrixXd points;
};

/// Inserts `t` `times` times. Preconditions: t inside the knot range and
/// multiplicity(t) + times <= degree. Linear in the points, so it also refines
/// homogeneous or identity "points" (how the extraction operators are built).
CurveNet insert_knot(const CurveNet& curve, double t, int times);

/// Inserts `t` `times` times in direction d (homogeneous, so rational surfaces
/// stay exact). Errors: t outside the open domain, or the resulting
/// multiplicity above the degree.
Result<BSplineSurface> insert_knot(const BSplineSurface& surface, Direction d, double t,
                                   int times = 1);

}  // namespace argil
