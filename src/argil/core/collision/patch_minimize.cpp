#include "argil/core/collision/patch_minimize.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

namespace argil {

namespace {

/// S and its derivatives on the rectangle: through the node's Bezier patch
/// when there is one (no knot search: the cheaper path at every leaf), else
/// through the B-spline.
class RectangleEvaluator {
 public:
  RectangleEvaluator(const BSplineSurface& s, const BezierPatch* patch, double u0, double u1,
                     double v0, double v1)
      : s_(s), patch_(patch), u0_(u0), v0_(v0), wu_(u1 - u0), wv_(v1 - v0) {
    if (patch_ && !(wu_ > 0.0 && wv_ > 0.0)) patch_ = nullptr;
  }
  Eigen::Vector3d point(double u, double v) const {
    return patch_ ? evaluate(*patch_, local_u(u), local_v(v)) : evaluate(s_, u, v);
  }
  SurfaceDerivatives derivatives(double u, double v, int order) const {
    if (!patch_) return evaluate_derivatives(s_, u, v, order);
    SurfaceDerivatives d = evaluate_derivatives(*patch_, local_u(u), local_v(v), order);
    d.du /= wu_;
    d.dv /= wv_;
    d.duu /= wu_ * wu_;
    d.duv /= wu_ * wv_;
    d.dvv /= wv_ * wv_;
    return d;
  }

 private:
  double local_u(double u) const { return std::clamp((u - u0_) / wu_, 0.0, 1.0); }
  double local_v(double v) const { return std::clamp((v - v0_) / wv_, 0.0, 1.0); }
  const BSplineSurface& s_;
  const BezierPatch* patch_;
  double u0_, v0_, wu_, wv_;
};

/// Best of the corners and the centre, value only.
PatchMinimum best_start(const RectangleEvaluator& at, double u0, double u1, double v0, double v1,
                        const std::function<DistanceSample(const Eigen::Vector3d&)>& f,
                        const std::array<Eigen::Vector3d, 4>* corners) {
  PatchMinimum best;
  best.value = std::numeric_limits<double>::infinity();
  // Start from the best of the corners and the centre.
  for (int a = 0; a <= 2; a += 2) {
    for (int b = 0; b <= 2; b += 2) {
      const double u = a == 0 ? u0 : u1;
      const double v = b == 0 ? v0 : v1;
      const Eigen::Vector3d x =
          corners ? (*corners)[static_cast<std::size_t>(a / 2 + b)] : at.point(u, v);
      const double value = f(x).value;
      if (value < best.value) {
        best.value = value;
        best.uv = {u, v};
      }
    }
  }
  {
    const double u = 0.5 * (u0 + u1), v = 0.5 * (v0 + v1);
    const double value = f(at.point(u, v)).value;
    if (value < best.value) {
      best.value = value;
      best.uv = {u, v};
    }
  }
  return best;
}

}  // namespace

PatchMinimum best_sample_on_patch(const BSplineSurface& s, double u0, double u1, double v0,
                                  double v1,
                                  const std::function<DistanceSample(const Eigen::Vector3d&)>& f,
                                  const std::array<Eigen::Vector3d, 4>* corners,
                                  const BezierPatch* patch) {
  const RectangleEvaluator at(s, patch, u0, u1, v0, v1);
  PatchMinimum best = best_start(at, u0, u1, v0, v1, f, corners);
  best.derivatives = at.derivatives(best.uv[0], best.uv[1], 1);
  return best;
}

PatchMinimum minimize_on_patch(const BSplineSurface& s, double u0, double u1, double v0, double v1,
                               const std::function<DistanceSample(const Eigen::Vector3d&)>& f,
                               const std::array<Eigen::Vector3d, 4>* corners,
                               const BezierPatch* patch) {
  const RectangleEvaluator at(s, patch, u0, u1, v0, v1);
  PatchMinimum best = best_start(at, u0, u1, v0, v1, f, corners);
  const Eigen::Vector2d lo(u0, v0), hi(u1, v1);
  const Eigen::Vector2d scale = (hi - lo).cwiseMax(std::numeric_limits<double>::min());
  Eigen::Vector2d uv = best.uv;
  constexpr int kMaxIterations = 30;
  for (int it = 0; it < kMaxIterations; ++it) {
    const SurfaceDerivatives d = at.derivatives(uv[0], uv[1], 2);
    const DistanceSample g = f(d.point);
    Eigen::Matrix<double, 3, 2> J;
    J << d.du, d.dv;
    const Eigen::Vector2d grad = J.transpose() * g.gradient;
    Eigen::Matrix2d H = J.transpose() * g.hessian * J;
    H(0, 0) += g.gradient.dot(d.duu);
    H(0, 1) += g.gradient.dot(d.duv);
    H(1, 0) += g.gradient.dot(d.duv);
    H(1, 1) += g.gradient.dot(d.dvv);
    // Variables at a bound with the gradient pushing outward stay fixed.
    Eigen::Vector2d free_mask(1.0, 1.0);
    for (int k = 0; k < 2; ++k) {
      if ((uv[k] <= lo[k] && grad[k] > 0) || (uv[k] >= hi[k] && grad[k] < 0)) free_mask[k] = 0.0;
    }
    Eigen::Vector2d step = Eigen::Vector2d::Zero();
    Eigen::Matrix2d Hf = H;
    for (int k = 0; k < 2; ++k) {
      if (free_mask[k] == 0.0) {
        Hf.row(k).setZero();
        Hf.col(k).setZero();
        Hf(k, k) = 1.0;
      }
    }
    const Eigen::Vector2d gf = grad.cwiseProduct(free_mask);
    // Exactly zero: Eigen's isZero() compares with an absolute 1e-12, which
    // stops the descent at once on models a few micrometres across.
    if ((gf.array() == 0.0).all()) break;
    Eigen::LLT<Eigen::Matrix2d> llt(Hf);
    if (llt.info() == Eigen::Success && Hf.determinant() > 0.0) {
      step = -llt.solve(gf);
    } else {
      // Not convex here: steepest descent scaled to a tenth of the rectangle.
      const Eigen::Vector2d dir = -gf.cwiseProduct(scale);
      step = dir / std::max(dir.cwiseQuotient(scale).cwiseAbs().maxCoeff(), 1e-300) * 0.1;
    }
    // Backtracking on the clamped step.
    double t = 1.0;
    bool moved = false;
    for (int k = 0; k < 30; ++k) {
      const Eigen::Vector2d trial = (uv + t * step).cwiseMax(lo).cwiseMin(hi);
      const double value = f(at.point(trial[0], trial[1])).value;
      if (value < g.value || (value <= g.value && trial != uv)) {
        moved = (trial - uv).cwiseQuotient(scale).cwiseAbs().maxCoeff() > 1e-15;
        uv = trial;
        break;
      }
      t *= 0.5;
    }
    best.iterations = it + 1;
    if (!moved) break;
  }
  best.uv = uv;
  best.derivatives = at.derivatives(uv[0], uv[1], 1);
  best.value = f(best.derivatives.point).value;
  return best;
}

}  // namespace argil
