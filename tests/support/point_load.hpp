#pragma once
// A point load for the deformation tests: the load pattern of one contact
// placed by its fractions of the face's parameter domain.

#include <Eigen/Core>

#include "argil/core/geometry/bspline_surface.hpp"

namespace argil::test {

/// contact_load_pattern of one contact at (u, v) = the fractions (a, b) of
/// the domain in u and v (0: its start, 1: its end) carrying the whole load:
/// one weight per control point, summing to 1.
Eigen::VectorXd pattern_at(const BSplineSurface& s, double a, double b);

}  // namespace argil::test
