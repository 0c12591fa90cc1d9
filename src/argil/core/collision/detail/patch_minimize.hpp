#pragma once
// Local minimisation of a function of the surface point over a parameter
// rectangle: the exact step at the leaves of every query.

#include <Eigen/Core>
#include <array>
#include <functional>

#include "argil/core/geometry/bezier.hpp"
#include "argil/core/geometry/bspline_surface.hpp"
#include "argil/core/geometry/evaluate.hpp"
#include "argil/core/geometry/implicit_tool.hpp"
#include "argil/core/geometry/param_rect.hpp"

namespace argil {

struct PatchMinimum {
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();
  double value = 0.0;              // f(S(uv))
  SurfaceDerivatives derivatives;  // of S at uv, to first order
  int iterations = 0;
};

/// The function minimised: f(x) with gradient and Hessian at a surface point x.
using PointFunction = std::function<DistanceSample(const Eigen::Vector3d&)>;

/// What the caller may already know about the rectangle (a hierarchy node
/// knows both); each saves work and leaves the result unchanged up to rounding.
struct PatchHints {
  /// S at the rectangle's corners in ParamRect::corner() order: saves four evaluations.
  const std::array<Eigen::Vector3d, 4>* corners = nullptr;
  /// The Bezier patch of exactly this rectangle: S is then evaluated through
  /// it, without a knot search.
  const BezierPatch* patch = nullptr;
};

/// The best of the corners and the centre of `rect`, with first derivatives
/// there: a contact sample without Newton iterations.
PatchMinimum best_sample_on_patch(const BSplineSurface& surface, const ParamRect& rect,
                                  const PointFunction& f, const PatchHints& hints = {});

/// Minimises g(u, v) = f(S(u, v)) over `rect` by projected Newton steps
/// (Hessian J^T H_f J + grad f . S'', gradient steps where it is not positive
/// definite) with backtracking, from the best of the corners and the centre.
/// Finds a local minimum; callers certify globality with their bounds.
PatchMinimum minimize_on_patch(const BSplineSurface& surface, const ParamRect& rect,
                               const PointFunction& f, const PatchHints& hints = {});

}  // namespace argil
