#pragma once
// Closest point on a surface by Newton's method from a nearby (u, v): the test
// oracle for "this point lies on the surface" and for chord errors.

#include <Eigen/Dense>
#include <algorithm>

#include "argil/core/geometry/evaluate.hpp"

namespace argil::test {

struct Projection {
  Eigen::Vector2d uv;
  double distance_mm = 0.0;
};

/// Minimises |S(u, v) - point|^2 from `start` with Newton steps on the gradient
/// (full second-order Hessian), clamped to the domain. Converges quadratically
/// when `start` is close, which the callers guarantee (known or interpolated uv).
inline Projection project(const BSplineSurface& s, const Eigen::Vector3d& point, Eigen::Vector2d uv,
                          int iterations = 30) {
  const Eigen::Vector2d lo(s.domain_start(Direction::u), s.domain_start(Direction::v));
  const Eigen::Vector2d hi(s.domain_end(Direction::u), s.domain_end(Direction::v));
  double best = (evaluate(s, uv.x(), uv.y()) - point).norm();
  Eigen::Vector2d best_uv = uv;
  for (int k = 0; k < iterations; ++k) {
    const SurfaceDerivatives d = evaluate_derivatives(s, uv.x(), uv.y(), 2);
    const Eigen::Vector3d r = d.point - point;
    const Eigen::Vector2d gradient(r.dot(d.du), r.dot(d.dv));
    Eigen::Matrix2d hessian;
    hessian << d.du.dot(d.du) + r.dot(d.duu), d.du.dot(d.dv) + r.dot(d.duv),
        d.du.dot(d.dv) + r.dot(d.duv), d.dv.dot(d.dv) + r.dot(d.dvv);
    Eigen::Vector2d step = hessian.ldlt().solve(-gradient);
    if (!step.allFinite()) break;
    uv = (uv + step).cwiseMax(lo).cwiseMin(hi);
    const double distance = (evaluate(s, uv.x(), uv.y()) - point).norm();
    if (distance < best) {
      best = distance;
      best_uv = uv;
    }
    if (step.norm() <= 1e-15 * (hi - lo).norm()) break;
  }
  return {best_uv, best};
}

}  // namespace argil::test
