#include "argil/core/collision/detail/patch_minimize.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace argil {

namespace {

/// S and its derivatives on the rectangle: through the node's Bezier patch
/// when there is one (no knot search: the cheaper path at every leaf), else
/// through the B-spline.
class RectangleEvaluator {
 public:
  RectangleEvaluator(const BSplineSurface& s, const ParamRect& rect, const BezierPatch* patch)
      : s_(s), patch_(patch), u0_(rect.u0), v0_(rect.v0), wu_(rect.width()), wv_(rect.height()) {
    if (patch_ && !(wu_ > 0.0 && wv_ > 0.0)) patch_ = nullptr;
  }
  Eigen::Vector3d point(const Eigen::Vector2d& uv) const {
    return patch_ ? evaluate(*patch_, local_u(uv[0]), local_v(uv[1])) : evaluate(s_, uv[0], uv[1]);
  }
  SurfaceDerivatives derivatives(const Eigen::Vector2d& uv, int order) const {
    if (!patch_) return evaluate_derivatives(s_, uv[0], uv[1], order);
    SurfaceDerivatives d = evaluate_derivatives(*patch_, local_u(uv[0]), local_v(uv[1]), order);
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
PatchMinimum best_start(const RectangleEvaluator& at, const ParamRect& rect, const PointFunction& f,
                        const std::array<Eigen::Vector3d, 4>* corners) {
  PatchMinimum best;
  best.value = std::numeric_limits<double>::infinity();
  const auto offer = [&](const Eigen::Vector2d& uv, const Eigen::Vector3d& x) {
    const double value = f(x).value;
    if (value < best.value) {
      best.value = value;
      best.uv = uv;
    }
  };
  for (int k : {0, 2, 1, 3}) {  // (u0,v0), (u0,v1), (u1,v0), (u1,v1): ties keep the first
    const Eigen::Vector2d uv = rect.corner(k);
    offer(uv, corners ? (*corners)[static_cast<std::size_t>(k)] : at.point(uv));
  }
  offer(rect.centre(), at.point(rect.centre()));
  return best;
}

/// The projected Newton step at uv from f's sample g and S's derivatives d:
/// variables at a bound with the gradient pushing outward stay fixed; where
/// the reduced Hessian is not positive definite, steepest descent scaled to a
/// tenth of the rectangle. Nullopt when the projected gradient vanishes.
std::optional<Eigen::Vector2d> newton_step(const SurfaceDerivatives& d, const DistanceSample& g,
                                           const Eigen::Vector2d& uv, const ParamRect& rect,
                                           const Eigen::Vector2d& scale) {
  Eigen::Matrix<double, 3, 2> J;
  J << d.du, d.dv;
  const Eigen::Vector2d grad = J.transpose() * g.gradient;
  Eigen::Matrix2d H = J.transpose() * g.hessian * J;
  H(0, 0) += g.gradient.dot(d.duu);
  H(0, 1) += g.gradient.dot(d.duv);
  H(1, 0) += g.gradient.dot(d.duv);
  H(1, 1) += g.gradient.dot(d.dvv);
  const Eigen::Vector2d lo = rect.lower(), hi = rect.upper();
  Eigen::Vector2d free_mask(1.0, 1.0);
  for (int k = 0; k < 2; ++k) {
    if ((uv[k] <= lo[k] && grad[k] > 0) || (uv[k] >= hi[k] && grad[k] < 0)) {
      free_mask[k] = 0.0;
      H.row(k).setZero();
      H.col(k).setZero();
      H(k, k) = 1.0;
    }
  }
  const Eigen::Vector2d gf = grad.cwiseProduct(free_mask);
  // Exactly zero: Eigen's isZero() compares with an absolute 1e-12, which
  // stops the descent at once on models a few micrometres across.
  if ((gf.array() == 0.0).all()) return std::nullopt;
  Eigen::LLT<Eigen::Matrix2d> llt(H);
  if (llt.info() == Eigen::Success && H.determinant() > 0.0) {
    return Eigen::Vector2d(-llt.solve(gf));
  }
  const Eigen::Vector2d dir = -gf.cwiseProduct(scale);
  return Eigen::Vector2d(dir / std::max(dir.cwiseQuotient(scale).cwiseAbs().maxCoeff(), 1e-300) *
                         0.1);
}

/// Backtracking on the clamped step from uv (where f is `value`): the first
/// trial that does not increase f, or nullopt when none does.
std::optional<Eigen::Vector2d> backtrack(const RectangleEvaluator& at, const PointFunction& f,
                                         const Eigen::Vector2d& uv, const Eigen::Vector2d& step,
                                         double value, const ParamRect& rect) {
  double t = 1.0;
  for (int k = 0; k < 30; ++k) {
    const Eigen::Vector2d trial = (uv + t * step).cwiseMax(rect.lower()).cwiseMin(rect.upper());
    const double trial_value = f(at.point(trial)).value;
    if (trial_value < value || (trial_value <= value && trial != uv)) return trial;
    t *= 0.5;
  }
  return std::nullopt;
}

}  // namespace

PatchMinimum best_sample_on_patch(const BSplineSurface& s, const ParamRect& rect,
                                  const PointFunction& f, const PatchHints& hints) {
  const RectangleEvaluator at(s, rect, hints.patch);
  PatchMinimum best = best_start(at, rect, f, hints.corners);
  best.derivatives = at.derivatives(best.uv, 1);
  return best;
}

PatchMinimum minimize_on_patch(const BSplineSurface& s, const ParamRect& rect,
                               const PointFunction& f, const PatchHints& hints) {
  const RectangleEvaluator at(s, rect, hints.patch);
  PatchMinimum best = best_start(at, rect, f, hints.corners);
  const Eigen::Vector2d scale =
      (rect.upper() - rect.lower()).cwiseMax(std::numeric_limits<double>::min());
  Eigen::Vector2d uv = best.uv;
  constexpr int kMaxIterations = 30;
  for (int it = 0; it < kMaxIterations; ++it) {
    const SurfaceDerivatives d = at.derivatives(uv, 2);
    const DistanceSample g = f(d.point);
    const std::optional<Eigen::Vector2d> step = newton_step(d, g, uv, rect, scale);
    if (!step) break;
    const std::optional<Eigen::Vector2d> next = backtrack(at, f, uv, *step, g.value, rect);
    best.iterations = it + 1;
    const bool moved = next && (*next - uv).cwiseQuotient(scale).cwiseAbs().maxCoeff() > 1e-15;
    if (next) uv = *next;
    if (!moved) break;
  }
  best.uv = uv;
  best.derivatives = at.derivatives(uv, 1);
  best.value = f(best.derivatives.point).value;
  return best;
}

}  // namespace argil
