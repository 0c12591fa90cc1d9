#pragma once
// Refining a session's deformable faces where its script takes the tool
// (docs/deformation.md, Refinement), before the first tick: a face too coarse
// for the tool (a 2 x 2 plane, a 7 x 2 cylinder) is elevated to degree 3 and
// its spans near the tool's path split to the scene's resolution, exactly (the
// shape and the trims do not change). The ticks never pay for it.

#include <Eigen/Core>
#include <vector>

#include "argil/core/geometry/local_refinement.hpp"
#include "argil/core/haptic/haptic_tick.hpp"
#include "argil/sculpt/scene/scene.hpp"

namespace argil::sculpt {

struct LoadedModel;

/// One face the refinement changed, for the run summary.
struct FaceRefinement {
  int model = 0;  // index in Scene::models
  int face = 0;   // face index in the model's file
  RefinementReport report;
};

/// Radius [mm] of the smallest sphere about the tool frame's origin holding
/// the tool (a sphere's radius; a B-spline tool's farthest control point).
double tool_bound_radius(const ToolShape& tool);

/// The scene's resolution, or (unset) the tool's bound radius, so about three
/// control points lie across the tool's width; 0 (a point tool): none.
double refinement_resolution(const Scene& scene, const ToolShape& tool);

/// Refines every face of every deformable model that comes within reach of
/// one of `paths` (the device's positions while engaged, in order; it moves
/// linearly between them), over the box of (u, v) near all of them: reach =
/// twice the tool's bound radius (the tool plus a press as deep) plus the
/// resolution. Faces already fine enough are left as they are. Returns the
/// faces it changed.
Result<std::vector<FaceRefinement>> refine_faces(
    std::vector<LoadedModel>& models, const ToolShape& tool, double resolution,
    const std::vector<std::vector<Eigen::Vector3d>>& paths);

/// "models[0] face 3: degree 1 x 1 -> 3 x 3, 2 x 2 -> 14 x 9 control points
/// (spans <= 0.5 mm near the tool)".
std::string refinement_text(const FaceRefinement& r);

}  // namespace argil::sculpt
