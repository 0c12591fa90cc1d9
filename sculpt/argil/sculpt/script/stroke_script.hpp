#pragma once
// Scripts generated from a place on a face: a press along the normal at one
// (u, v), or a drag along the surface through several (u, v), at a depth, so
// that nobody computes device coordinates by hand (`argil script`).

#include <Eigen/Core>
#include <string>
#include <vector>

#include "argil/core/base/status.hpp"
#include "argil/io/model/model.hpp"
#include "argil/sculpt/script/script.hpp"

namespace argil::sculpt {

/// Where and how the tool goes. One (u, v): a press; two or more: a drag
/// through them, in (u, v) straight lines between consecutive points.
struct StrokeRequest {
  std::vector<Eigen::Vector2d> uv;  // on the face's surface, inside its trims
  double depth_mm = 1.0;            // how far the tool goes below the surface, > 0
  double speed_mm_s = 10.0;         // device speed, > 0
  double approach_mm = 10.0;        // start and end this far above the surface, > 0
  double hold_s = 0.5;              // a press rests this long at its depth, >= 0
  /// From the device point to the tool's lowest point along the normal: a
  /// sphere's radius, 0 for a point tool.
  double tool_offset_mm = 0.0;
  std::string tool;  // the scene tool the script names (empty: the scene's first)
};

/// The script of one stroke on `face` (its outward normal: -S_u x S_v on a
/// reversed face). The device comes down the normal from approach_mm above
/// the first point, engages a tenth of the approach above the surface, sinks
/// to depth_mm, then holds (a press) or follows the surface at that depth
/// through the points (a drag; keyframes every chord of at most `step_mm`,
/// timed by the device's path length at speed_mm_s), rises to a tenth of the
/// approach, releases, and lifts to approach_mm. Errors name `face_label`
/// and the point: a (u, v) outside the surface's domain or its trims (a drag
/// checked at every keyframe), a depth, speed, approach or hold out of range,
/// or a normal that vanishes (a pole).
Result<Script> stroke_script(const io::FaceRecord& face, const StrokeRequest& request,
                             const std::string& face_label, double step_mm);

}  // namespace argil::sculpt
