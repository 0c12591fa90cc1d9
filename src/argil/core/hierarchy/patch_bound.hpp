#pragma once
// Conservative bounds of a Bezier (sub-)patch from its control points alone.

#include <Eigen/Core>
#include <array>

#include "argil/core/geometry/bezier.hpp"
#include "argil/core/geometry/bspline_surface.hpp"

namespace argil {

/// Bounds of a rational or polynomial Bezier patch. With positive weights the
/// patch lies in the convex hull of its Cartesian control points, so the
/// sphere and the box enclose it; never built from sample points.
struct PatchBound {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  // sphere centre [mm]
  double radius = 0.0;                               // sphere radius [mm]
  Box3 box{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  /// Bound [mm] on |S(s, t) - T(s, t)| over [0, 1]^2, where T is the pair of
  /// triangles (c00, c10, c11), (c00, c11, c01) through the corners with the
  /// same parameters: net-to-bilinear distance, a rational term that vanishes
  /// as the weights even out, and the bilinear-to-triangles term.
  double flatness = 0.0;
  // S(0,0), S(1,0), S(0,1), S(1,1)
  std::array<Eigen::Vector3d, 4> corners{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                                         Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
};

PatchBound bound_patch(const BezierPatch& patch);

}  // namespace argil
