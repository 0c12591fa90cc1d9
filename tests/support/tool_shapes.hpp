#pragma once
// Small surfaces the haptic tests and benchmarks share: clamped uniform
// knots, a wavy bicubic sheet and the 12 mm bowl-shaped cap used as a
// B-spline tool.

#include <Eigen/Core>

#include "argil/core/geometry/bspline_surface.hpp"

namespace argil::test {

/// Clamped uniform knots on [0, 1] for `poles` poles of `degree`.
Eigen::VectorXd uniform_knots(int degree, int poles);

/// n x n bicubic poles `pitch` [mm] apart over (x, y), height
/// wave * sin(0.7 i) * cos(0.5 j) [mm] at pole (i, j).
BSplineSurface wavy_sheet(int n, double pitch, double wave);

/// A bowl-shaped bicubic cap 12 mm wide and 2.4 mm tall (4 x 4 poles,
/// z = 0.05 (x^2 + y^2)), lowest near its frame origin.
BSplineSurface bowl_cap();

}  // namespace argil::test
