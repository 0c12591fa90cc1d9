#pragma once
// The contact record at a surface point, built from the surface's derivatives
// there: the one place every query turns a parameter pair into a Contact.

#include <Eigen/Core>

#include "argil/core/collision/contact.hpp"
#include "argil/core/geometry/bspline_surface.hpp"
#include "argil/core/geometry/evaluate.hpp"

namespace argil {

/// Contact on surface a at `uv_a`, where `d` holds S and its first
/// derivatives (from either the B-spline or a Bezier patch of it, rescaled to
/// the surface's parameters): point S, unit normal S_u x S_v (at a pole, where
/// that vanishes, the limit normal from the surface's second derivatives),
/// tangents S_u, S_v [mm per unit parameter], and `depth` [mm]. uv_b and
/// region keep their defaults.
Contact contact_at(const BSplineSurface& a, const Eigen::Vector2d& uv_a,
                   const SurfaceDerivatives& d, double depth);

}  // namespace argil
