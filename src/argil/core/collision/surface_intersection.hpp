#pragma once
// Surface against surface (docs/collision.md): simultaneous descent over node
// pairs of two conservative hierarchies, triangle-triangle tests at flat leaf
// pairs, intersection curves with (u, v) on both surfaces, near-touching
// contacts, and optional Newton refinement onto both exact surfaces.

#include <Eigen/Core>

#include "argil/core/collision/contact.hpp"
#include "argil/core/geometry/bspline_surface.hpp"
#include "argil/core/geometry/pose.hpp"
#include "argil/core/hierarchy/surface_hierarchy.hpp"

namespace argil {

/// Intersections and near-touches of surfaces a and b within eps =
/// request.tolerance [mm].
///
/// Descent: node pairs are pruned when their spheres, then their boxes, are
/// more than eps apart; otherwise the node that is not yet flat (the larger
/// sphere when both are not) is split. A node is flat when its flatness bound
/// is at most eps/3 (or its radius at most eps/6, or it sits at
/// request.max_level). At a pair of flat nodes each node is replaced by its two
/// corner triangles, which lie within eps/3 of the surface at the same
/// parameters, and the four triangle pairs are intersected.
///
/// The eps budget: eps/3 for a's triangles, eps/3 for b's, and eps/3 of
/// touching margin, so a leaf pair is a contact when its triangles cross or
/// are at most eps apart. Then
/// - every point where the surfaces cross, or come within eps/3 of each
///   other, lies in a reported leaf pair (no intersection is missed);
/// - every reported point lies within eps/3 (curve points) or 5 eps/6
///   (near-touch contacts) of both surfaces, before refinement.
///
/// Results: `curves` are the triangle intersection segments chained where
/// their end points coincide (3D distance at most eps and parameters within
/// half a leaf on both surfaces); each point carries (u, v) on a and b by
/// barycentric interpolation of the leaf's parameter corners. A segment where
/// the surfaces are tangent over its leaf pair (exact normals parallel to
/// within eps over the larger leaf: faces lying on each other) is no curve
/// piece; its leaf pair's contact reports it. `contacts` has
/// one record per leaf pair in contact: on its longest crossing segment's
/// midpoint (depth 0), or halfway between the closest triangle points
/// (depth = -their distance, just apart). Normal and tangents are a's, from
/// its derivatives. Contacts whose leaf rectangles on a touch form a region.
///
/// With request.refine, every curve point and crossing contact is moved onto
/// both exact surfaces by Gauss-Newton on S_a(u, v) = S_b(s, t) with a plane
/// constraint across the curve (or the domain edge it lies on), to ~1e-12 of
/// the model size; near-touch contacts move to a local closest pair, with
/// depth = -gap (0 when the surfaces turn out to cross there). A point whose
/// iteration does not converge near its leaf keeps its unrefined value.
CollisionResult collide(const SurfaceHierarchy& a, const SurfaceHierarchy& b,
                        const CollisionRequest& request = {});

/// The same query with b placed rigidly in a's frame by X_AB (b's hierarchy
/// stays in its own frame B): a rigid tool moved every tick keeps every bound
/// it has built instead of re-bounding its control net at each pose. Spheres,
/// corner triangles and flatness move exactly and boxes become the boxes
/// around the moved boxes, so the guarantees above hold unchanged. Results are
/// in a's frame (uv_b on b's own parameters). It finds what collide(a, b')
/// finds for b' = b moved by X_AB, up to rounding and the extra leaf pairs
/// the looser boxes let through (which add nothing); the tolerance is checked
/// against b's bounds in its own frame.
CollisionResult collide(const SurfaceHierarchy& a, const SurfaceHierarchy& b, const Pose& X_AB,
                        const CollisionRequest& request = {});

/// The query at X_AB_to, for b moved there from X_AB_from (rotation by slerp,
/// translation on a line). When nothing crosses at X_AB_to, a leaf pair that
/// meets at some time of the motion counts as crossing: the first one found
/// adds a contact of depth 0 on a, at a point where they met. So a motion that
/// starts clear and reports no crossing never passed through a, however thin
/// b is along the motion.
/// Leaves' corners are taken to move on straight lines between their two
/// placements. For a translation that is exact. With a rotation, node bounds
/// stay conservative (widened by the arcs' sagitta |x| (1 - cos(angle / 2))
/// for a point's distance |x| from b's origin), but the leaf test's model of
/// the motion strays from the real one: by the sagitta in a's frame, and, for
/// a's corners seen from b, by about |a - p| (1 - cos(angle / 2)) +
/// |translation| sin(angle / 4); an edge's swept quad is also twisted by up
/// to |edge| sin(angle / 2) / 2. The model's path joins the same two
/// placements within those errors, so a leaf that passes through a farther
/// than them from a's edges is found; a graze (meeting a and leaving it on the
/// same side) shallower than them may be missed or reported. Callers keep the
/// rotation of one query small.
/// The way is looked at only when collide(a, b, X_AB_to, request), run first,
/// crosses nowhere, so a motion that meets nothing on the way returns exactly
/// that query's result. A leaf pair whose end triangles are farther apart than
/// any point of b moved never met and is skipped (this also drops the model's
/// false grazes beyond that distance). For a motion within the tolerance the
/// end's descent has already reached every other pair and the leaf test runs
/// on those alone; a longer motion gets a second descent with bounds over the
/// whole way (many more pairs), stopping at the first pair that meets.
CollisionResult collide_swept(const SurfaceHierarchy& a, const SurfaceHierarchy& b,
                              const Pose& X_AB_from, const Pose& X_AB_to,
                              const CollisionRequest& request = {});

}  // namespace argil
