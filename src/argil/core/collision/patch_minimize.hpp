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

namespace argil {

struct PatchMinimum {
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();
  double value = 0.0;              // f(S(uv))
  SurfaceDerivatives derivatives;  // of S at uv, to first order
  int iterations = 0;
};

/// The best of the corners and the centre of the rectangle, with first
/// derivatives there: a contact sample without Newton iterations.
/// `corners`, when given, are S at (u0,v0), (u1,v0), (u0,v1), (u1,v1).
/// `patch`, when given, is the Bezier patch of exactly this rectangle (a
/// hierarchy node's): S is then evaluated through it, without a knot search.
PatchMinimum best_sample_on_patch(const BSplineSurface& surface, double u0, double u1, double v0,
                                  double v1,
                                  const std::function<DistanceSample(const Eigen::Vector3d&)>& f,
                                  const std::array<Eigen::Vector3d, 4>* corners = nullptr,
                                  const BezierPatch* patch = nullptr);

/// Minimises g(u, v) = f(S(u, v)) over [u0, u1] x [v0, v1] by projected
/// Newton steps (Hessian J^T H_f J + grad f . S'', gradient steps where it is
/// not positive definite) with backtracking, from the best of the corners and the centre.
/// Finds a local minimum; callers certify globality with their bounds.
/// `corners`, when given, are S at (u0,v0), (u1,v0), (u0,v1), (u1,v1) (a
/// hierarchy node has them), saving four evaluations; `patch` as above.
PatchMinimum minimize_on_patch(const BSplineSurface& surface, double u0, double u1, double v0,
                               double v1,
                               const std::function<DistanceSample(const Eigen::Vector3d&)>& f,
                               const std::array<Eigen::Vector3d, 4>* corners = nullptr,
                               const BezierPatch* patch = nullptr);

}  // namespace argil
