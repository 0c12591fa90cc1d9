#pragma once
// Newton refinement of a point pair onto two exact surfaces: the last step of
// the surface-surface query for curve points and contacts.

#include <Eigen/Core>
#include <optional>

#include "argil/core/geometry/bspline_surface.hpp"
#include "argil/core/operators/patch_evaluator.hpp"

namespace argil {

/// The evaluators refinement reads both surfaces through, and the model size
/// [mm] refinement tolerances scale with. One query's: refinement updates the
/// evaluators' kept patches even through a const SurfacePair, so one pair is
/// never refined on from two threads at once.
struct SurfacePair {
  PatchEvaluator& eval_a;
  PatchEvaluator& eval_b;
  double scale;

  const BSplineSurface& a() const { return eval_a.surface(); }
  const BSplineSurface& b() const { return eval_b.surface(); }
};

/// A point with its parameters on both surfaces.
struct PairPoint {
  Eigen::Vector3d point;
  Eigen::Vector2d uv_a, uv_b;
};

/// Where refine_surface_pair() starts and what it keeps fixed.
struct PairRefineRequest {
  Eigen::Vector2d uv_a = Eigen::Vector2d::Zero();  // start on surface a
  Eigen::Vector2d uv_b = Eigen::Vector2d::Zero();  // start on surface b
  /// Keep the point from sliding along the intersection curve: a parameter
  /// that starts exactly on its domain edge stays there; otherwise the point
  /// stays on the plane through the start point across the curve (normal
  /// n_a x n_b there). Without it (or where the surfaces are tangent) the
  /// iteration converges to a local minimum of |S_a - S_b|: a local closest pair.
  bool on_curve = false;
  /// With on_curve: the parameter (0 to 3: u_a, v_a, u_b, v_b) that stays
  /// where it starts instead of the plane, so a point on a leaf's edge
  /// refines to where the curve crosses that edge; -1 for none.
  int fixed = -1;
  /// Model size [mm]: the iteration stops when |S_a - S_b| <= 1e-14 of it.
  double scale = 1.0;
};

/// The direction of the intersection curve at a point on both surfaces: its
/// unit tangent n_a x n_b and the rates of both parameter pairs along it per
/// mm of arc; all zero where the surfaces are tangent (or a normal vanishes).
struct CurveTangent {
  Eigen::Vector3d unit = Eigen::Vector3d::Zero();
  Eigen::Vector2d uv_a = Eigen::Vector2d::Zero();
  Eigen::Vector2d uv_b = Eigen::Vector2d::Zero();
};

CurveTangent curve_tangent(PatchEvaluator& a, PatchEvaluator& b, const Eigen::Vector2d& uv_a,
                           const Eigen::Vector2d& uv_b);

/// A pair of surface points after refine_surface_pair().
struct RefinedPair {
  Eigen::Vector2d uv_a = Eigen::Vector2d::Zero();
  Eigen::Vector2d uv_b = Eigen::Vector2d::Zero();
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // midpoint of S_a(uv_a) and S_b(uv_b) [mm]
  double gap = 0.0;                                 // |S_a(uv_a) - S_b(uv_b)| [mm]
  int iterations = 0;
  CurveTangent tangent;  // at (uv_a, uv_b)
};

/// Gauss-Newton from (uv_a, uv_b) on F = S_a(u, v) - S_b(s, t) with
/// minimum-norm steps in the 4 parameters (columns scaled to unit norm),
/// clamped to both domains. Stops when |F| <= 1e-14 of `scale`, when |F|
/// stops halving after the first iterations, or when the step stalls; at most
/// 40 iterations.
RefinedPair refine_surface_pair(PatchEvaluator& a, PatchEvaluator& b,
                                const PairRefineRequest& request);

/// Refines one point pair from `start` (on the curve: see
/// PairRefineRequest::on_curve and fixed); nullopt when refinement leaves the
/// `reach` of the start [mm] or, on a curve, does not converge onto both
/// surfaces (to 1e-12 of the model size).
std::optional<RefinedPair> refine_near(const SurfacePair& pair, const PairPoint& start,
                                       bool on_curve, double reach, int fixed = -1);

}  // namespace argil
