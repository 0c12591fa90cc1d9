#pragma once
// The best-first closest-point search on a surface hierarchy, shared by the
// point tool on whole and on trimmed surfaces. Private to the collision module.

#include <Eigen/Core>
#include <limits>

#include "argil/core/collision/implicit_contact.hpp"
#include "argil/core/geometry/trim_region.hpp"
#include "argil/core/hierarchy/surface_hierarchy.hpp"

namespace argil {

/// How closest_point_search runs.
struct ClosestSearchOptions {
  double eps = 1e-3;  // [mm]: stop when no node can beat the best by eps
  /// Only points whose (u, v) this region contains are candidates (every
  /// point when null or empty).
  const TrimRegion* trim = nullptr;
  /// A distance already reached elsewhere [mm] (a trimmed edge): only nodes
  /// that can beat it are searched.
  double bound = std::numeric_limits<double>::infinity();
};

/// What the search found.
struct ClosestFound {
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();
  /// |p - S(uv)| [mm]; +infinity when no candidate beat options.bound.
  double distance = std::numeric_limits<double>::infinity();
};

/// Best-first search on the hierarchy ordered by each node's lower bound (its
/// sphere, and its corner triangles less its flatness), patch corners as free
/// upper bounds, Newton projection at flat leaves. Without a trim the result
/// is within eps of the global minimum (uv defaults to the domain's lower
/// corner only for a surface with no nodes).
ClosestFound closest_point_search(const SurfaceHierarchy& h, const Eigen::Vector3d& p,
                                  const ClosestSearchOptions& options, QueryCounters& counters);

/// The point of the trimmed face's edge (the image of the trim boundary)
/// closest to p, within eps: best-first over the hierarchy nodes the boundary
/// may touch (each piece's control-point box against the node's rectangle),
/// ordered by the nodes' certified lower bounds; at each leaf the pieces
/// touching it are searched once each (TrimRegion::closest_on_piece, local per
/// piece). Distance +infinity for an empty region.
TrimEdgePoint closest_edge_search(const SurfaceHierarchy& h, const TrimRegion& trim,
                                  const Eigen::Vector3d& p, double eps, QueryCounters& counters);

/// The ClosestPoint record of surface point uv for query point p: point,
/// distance, unit normal (limit normal at a pole) and signed distance.
ClosestPoint closest_point_at(const BSplineSurface& surface, const Eigen::Vector2d& uv,
                              const Eigen::Vector3d& p, const QueryCounters& counters);

}  // namespace argil
