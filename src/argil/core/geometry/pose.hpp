#pragma once
// A rigid pose X_AB: the frame B in the frame A, as a rotation R_AB and the
// position p_AB of B's origin [mm]. One type from the script to the tick:
// device samples, keyframes and the tool proxy all hold a Pose named by its
// frames (docs/conventions.md).

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace argil {

/// X_AB maps a point given in B to A: p_A = R * p_B + p. R is a unit
/// quaternion; the helpers below keep it unit when their inputs are.
struct Pose {
  Eigen::Quaterniond R = Eigen::Quaterniond::Identity();  // R_AB
  Eigen::Vector3d p = Eigen::Vector3d::Zero();            // p_AB [mm]

  static Pose identity() { return {}; }
  /// A pure translation (R = identity).
  static Pose at(const Eigen::Vector3d& position) {
    return {Eigen::Quaterniond::Identity(), position};
  }
};

/// Composition: X_AC = X_AB * X_BC.
Pose operator*(const Pose& X_AB, const Pose& X_BC);
/// X_BA from X_AB.
Pose inverse(const Pose& X_AB);
/// p_A = X_AB * p_B.
Eigen::Vector3d apply(const Pose& X_AB, const Eigen::Vector3d& p_B);
/// The pose a fraction t in [0, 1] of the way from a to b: position linear,
/// rotation by slerp.
Pose interpolate(const Pose& a, const Pose& b, double t);

}  // namespace argil
