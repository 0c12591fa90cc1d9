#pragma once
// Exact degree elevation of a surface in one direction: the same surface
// (the same point at every (u, v)) on a net of higher degree, every distinct
// knot's multiplicity raised with the degree so each join keeps its
// continuity. A face of degree 1 or 2 (a plane, a cylinder) gets the interior
// control points a press needs without changing its shape.

#include "argil/core/base/status.hpp"
#include "argil/core/geometry/bspline_surface.hpp"

namespace argil {

/// `surface` with degree p + `times` in direction d (times >= 0). Computed in
/// homogeneous coordinates (rational faces stay exact, weights included) by
/// collocation at the new net's Greville abscissae, where the collocation
/// matrix is non-singular (Schoenberg-Whitney); the new space contains the old
/// one, so the fit reproduces the surface to rounding (measured against
/// OpenCASCADE's IncreaseDegree in the tests). Errors: times < 0, or a degree
/// above kMaxElevatedDegree.
Result<BSplineSurface> elevate_degree(const BSplineSurface& surface, Direction d, int times);

/// Highest degree elevate_degree produces.
inline constexpr int kMaxElevatedDegree = 15;

}  // namespace argil
