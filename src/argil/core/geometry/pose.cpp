#include "argil/core/geometry/pose.hpp"

namespace argil {

Pose operator*(const Pose& X_AB, const Pose& X_BC) {
  return {X_AB.R * X_BC.R, X_AB.R * X_BC.p + X_AB.p};
}

Pose inverse(const Pose& X_AB) {
  const Eigen::Quaterniond R_BA = X_AB.R.conjugate();
  return {R_BA, -(R_BA * X_AB.p)};
}

Eigen::Vector3d apply(const Pose& X_AB, const Eigen::Vector3d& p_B) {
  return X_AB.R * p_B + X_AB.p;
}

Pose interpolate(const Pose& a, const Pose& b, double t) {
  return {a.R.slerp(t, b.R), a.p + t * (b.p - a.p)};
}

}  // namespace argil
