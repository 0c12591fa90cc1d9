#pragma once
// Shared by direct and grid evaluation: derivatives of the homogeneous surface
// (w P, w) and the quotient rule that turns them into Cartesian derivatives.

#include <Eigen/Core>

#include "argil/core/geometry/evaluate.hpp"

namespace argil::detail {

/// A^(k,l) = d^(k+l)/du^k dv^l of sum N_i(u) N_j(v) (w P, w), for k + l <= 2.
struct HomogeneousDerivatives {
  Eigen::Vector4d a00 = Eigen::Vector4d::Zero();
  Eigen::Vector4d a10 = Eigen::Vector4d::Zero();
  Eigen::Vector4d a01 = Eigen::Vector4d::Zero();
  Eigen::Vector4d a20 = Eigen::Vector4d::Zero();
  Eigen::Vector4d a11 = Eigen::Vector4d::Zero();
  Eigen::Vector4d a02 = Eigen::Vector4d::Zero();
};

/// Quotient rule (The NURBS Book A4.4, written out for order <= 2).
inline SurfaceDerivatives cartesian(const HomogeneousDerivatives& h, int order) {
  SurfaceDerivatives d;
  const double w = h.a00[3];
  d.point = h.a00.head<3>() / w;
  if (order >= 1) {
    d.du = (h.a10.head<3>() - h.a10[3] * d.point) / w;
    d.dv = (h.a01.head<3>() - h.a01[3] * d.point) / w;
  }
  if (order >= 2) {
    d.duu = (h.a20.head<3>() - 2.0 * h.a10[3] * d.du - h.a20[3] * d.point) / w;
    d.duv = (h.a11.head<3>() - h.a10[3] * d.dv - h.a01[3] * d.du - h.a11[3] * d.point) / w;
    d.dvv = (h.a02.head<3>() - 2.0 * h.a01[3] * d.dv - h.a02[3] * d.point) / w;
  }
  return d;
}

}  // namespace argil::detail
