#pragma once
// Surface against implicit tools (plane, sphere, capsule, box, ellipsoid,
// torus, user SDF) and against a point tool (closest point).

#include <Eigen/Core>

#include "argil/core/collision/contact.hpp"
#include "argil/core/geometry/implicit_tool.hpp"
#include "argil/core/hierarchy/surface_hierarchy.hpp"

namespace argil {

/// Contacts between the surface and the tool: every surface point where the
/// tool's function is at most eps (touching counts) is within eps of a
/// reported contact's region; no region deeper than eps is missed.
/// Descent: a node is pruned when f(centre) - L radius > eps; it is a leaf
/// when its flatness is at most eps and either a local minimum on it is in
/// contact or L radius <= eps (then nothing on it is deeper than eps).
CollisionResult collide(const SurfaceHierarchy& surface, const ImplicitTool& tool,
                        const CollisionRequest& request = {});

/// Closest point on the surface to p_W (the point tool / proxy).
struct [[nodiscard]] ClosestPoint {
  /// Not ok when the request is outside the documented range (check_request());
  /// then nothing was searched and the distances are NaN.
  Status status;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();
  double distance = 0.0;         // |p - S(uv)| [mm], within eps of the global minimum
  double signed_distance = 0.0;  // positive on the side the normal points to
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  /// True when the point lies on a trimmed face's edge rather than inside its
  /// material (closest_point on a TrimmedSurface only).
  bool on_edge = false;
  QueryCounters counters;
};

/// Best-first search on the hierarchy ordered by the sphere lower bound, then
/// Newton projection at leaves; stops when no node can beat the best by eps.
ClosestPoint closest_point(const SurfaceHierarchy& surface, const Eigen::Vector3d& p_W,
                           const CollisionRequest& request = {});

}  // namespace argil
