#pragma once
// Knot insertion (The NURBS Book A5.1): refines the knot vector without
// changing the curve or surface.

#include <Eigen/Core>

#include "argil/core/base/status.hpp"
#include "argil/core/geometry/bspline_curve.hpp"
#include "argil/core/geometry/bspline_surface.hpp"

namespace argil {

/// Inserts `t` `times` times. Preconditions: t inside the knot range and
/// multiplicity(t) + times <= degree. A rational curve is refined in
/// homogeneous coordinates, so it stays exact. Linear in the points, so it
/// also refines identity "points" (how the extraction operators are built).
BSplineCurve insert_knot(const BSplineCurve& curve, double t, int times);

/// Inserts `t` `times` times in direction d (homogeneous, so rational surfaces
/// stay exact). Errors: t outside the open domain, or the resulting
/// multiplicity above the degree.
Result<BSplineSurface> insert_knot(const BSplineSurface& surface, Direction d, double t,
                                   int times = 1);

}  // namespace argil
