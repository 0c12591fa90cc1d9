#pragma once
// Contact with material only: queries on a trimmed face count the points whose
// (u, v) lies inside the face's trim region, and where a tool reaches past the
// material it touches the face's edge (the image of the trim boundary).

#include <Eigen/Core>

#include "argil/core/collision/contact.hpp"
#include "argil/core/collision/implicit_contact.hpp"
#include "argil/core/geometry/trim_region.hpp"
#include "argil/core/hierarchy/surface_hierarchy.hpp"

namespace argil {

/// A surface and the part of its domain that is material.
struct TrimmedSurface {
  const SurfaceHierarchy* hierarchy = nullptr;
  const TrimRegion* trim = nullptr;  // null or empty: the whole domain is material
};

/// Closest point of the material to p_W. When the whole surface's closest
/// point (closest_point(hierarchy, p_W)) lies inside the trim, it is the
/// answer. Otherwise the answer is the nearer of the edge's closest point
/// (`on_edge` is then true and `normal` is the surface normal there) and the
/// closest point inside the trim. The edge's is found by a best-first search
/// over the hierarchy nodes the trim boundary may touch, ordered by their
/// certified lower bounds, with a local search on each boundary piece reached
/// (TrimRegion::closest_on_piece); the inside one by a second closest-point
/// search that offers only points the trim contains and visits only nodes
/// that can beat the edge. Errors as closest_point(hierarchy, p_W).
ClosestPoint closest_point(const TrimmedSurface& surface, const Eigen::Vector3d& p_W,
                           const CollisionRequest& request = {});

/// Contacts of the ball of `radius` [mm] around p_WC with the material: the
/// contacts of collide(hierarchy, sphere) whose uv_a the trim contains, and,
/// when any was left out, one edge contact where the edge comes closest to
/// the centre if that is within radius + eps: point S(c(t)) with uv_a = c(t),
/// depth radius - distance, and `normal` the unit vector from the edge point
/// to the centre (the surface normal when the centre is on the edge). It joins
/// the region of the left-out contact nearest to it; regions are then ranked
/// and kept to max_contacts as collide() does (every contact is looked at
/// before that, so those off the material do not crowd out the ones on it).
/// Untrimmed: collide() itself.
CollisionResult collide_sphere(const TrimmedSurface& surface, const Eigen::Vector3d& p_WC,
                               double radius, const CollisionRequest& request = {});

}  // namespace argil
