#pragma once
// Direct evaluation of points, derivatives up to second order and normals of a
// B-spline or NURBS surface at one parameter pair.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "argil/core/geometry/bspline_surface.hpp"

namespace argil {

/// Position and partial derivatives of S at (u, v) [mm, mm per unit parameter].
/// Entries above the requested order are zero.
struct SurfaceDerivatives {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d du = Eigen::Vector3d::Zero();
  Eigen::Vector3d dv = Eigen::Vector3d::Zero();
  Eigen::Vector3d duu = Eigen::Vector3d::Zero();
  Eigen::Vector3d duv = Eigen::Vector3d::Zero();
  Eigen::Vector3d dvv = Eigen::Vector3d::Zero();
};

/// Point S(u, v). (u, v) is clamped to the domain. Precondition: validate(surface).ok().
Eigen::Vector3d evaluate(const BSplineSurface& surface, double u, double v);

/// Point and derivatives up to `order` (0, 1 or 2), rational surfaces through
/// the quotient rule on homogeneous derivatives (The NURBS Book A3.6, A4.4).
SurfaceDerivatives evaluate_derivatives(const BSplineSurface& surface, double u, double v,
                                        int order = 2);

/// Unit normal S_u x S_v / |S_u x S_v| from first derivatives, or the zero
/// vector where the surface is degenerate: |S_u x S_v| at most 64 ulps of
/// max(|S_u|, |S_v|)^2 (a collapsed edge or pole, where one tangent is noise).
Eigen::Vector3d unit_normal(const SurfaceDerivatives& d);

/// Unit normal at (u, v), defined also on a collapsed edge (a pole), where one
/// tangent vanishes along a whole iso-line: there it is the limit of the
/// normal from inside the domain. With S_v = 0 along u = u*, S_v(u* + h, v) =
/// h S_uv + O(h^2), so the normal tends to +-S_u x S_uv; likewise +-S_uv x S_v
/// when S_u collapses. The sign is the side the domain lies on (the side of
/// larger parameter, except on the domain's end). Zero where the limit is not
/// defined either (both tangents vanish, or S_uv is parallel to the remaining
/// tangent). (u, v) is clamped to the domain. Precondition: validate(surface).ok().
Eigen::Vector3d unit_normal(const BSplineSurface& surface, double u, double v);

}  // namespace argil
