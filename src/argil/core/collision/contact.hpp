#pragma once
// The request/result shape shared by every collision query.

#include <Eigen/Core>
#include <vector>

#include "argil/core/base/status.hpp"
#include "argil/core/hierarchy/surface_hierarchy.hpp"

namespace argil {

class TrimRegion;

/// What a collision query should do. Lengths in model units [mm].
struct CollisionRequest {
  /// eps: certified geometric tolerance. Leaves are Bezier sub-patches whose
  /// flatness bound is at most eps; touching within eps counts as contact.
  double tolerance = 1e-3;
  int max_contacts = 256;
  /// Newton refinement of contact points on the exact surface.
  bool refine = true;
  /// Signed penetration depth per contact.
  bool compute_depth = true;
  /// Surface-surface queries: deepest hierarchy level the descent splits to.
  /// A node at this level counts as flat whatever its flatness bound, so a
  /// level below the one eps needs trades the eps guarantee for time.
  int max_level = SurfaceHierarchy::kMaxLevel;
  /// Surface-surface queries: a yes/no crossing test. The descent stops at the
  /// first leaf pair whose triangles cross (the result then holds that one
  /// contact, with depth 0, and its segments unless the surfaces are tangent
  /// there); near-touches are not looked for.
  /// An empty result means no crossing.
  bool first_crossing_only = false;
  /// Surface-surface queries: chain the crossing segments into curves (then
  /// refined and tidied). False for callers that use only the contacts, like
  /// the haptic tick: curves stay empty, and a crossing still shows as a
  /// contact of depth 0 (the deepest region's deepest contact is always kept).
  bool curves = true;
  /// Surface-surface queries: the contact query, but the descent stops at the
  /// first leaf pair whose triangles cross, so the contacts (and curves) are
  /// then only those found so far, that crossing among them. For callers that
  /// use the contacts only when nothing crosses: a crossing then costs what
  /// the yes/no test costs, not a descent over the whole overlap.
  bool stop_at_crossing = false;
  /// Surface-surface queries on a trimmed face a: the part of a's domain that
  /// is material (null or empty: all of it). Contacts whose uv_a it does not
  /// contain, crossings included, go to CollisionResult::off_material instead
  /// of `contacts`, before either is ranked and kept to max_contacts, so a
  /// face whose material is a small part of the overlap keeps max_contacts of
  /// its own.
  const TrimRegion* material_a = nullptr;
};

/// A polyline along the intersection of two surfaces: points [mm] and their
/// parameters on surface a and on surface b, one entry per point. A closed
/// curve repeats its first point at the end.
struct IntersectionCurve {
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector2d> uv_a, uv_b;

  /// Length of the polyline [mm].
  double length() const {
    double l = 0.0;
    for (std::size_t k = 0; k + 1 < points.size(); ++k) l += (points[k + 1] - points[k]).norm();
    return l;
  }
  /// True when the last point repeats the first (the parameters may differ
  /// across a periodic face's seam).
  bool closed() const { return points.size() > 2 && points.front() == points.back(); }
};

/// One contact between a surface (side a) and a tool or second surface (side b).
struct Contact {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();      // p_WC on surface a [mm]
  Eigen::Vector2d uv_a = Eigen::Vector2d::Zero();       // parameters on surface a
  Eigen::Vector2d uv_b = Eigen::Vector2d::Zero();       // parameters on surface b, if any
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();     // unit normal of a (limit at a pole)
  Eigen::Vector3d tangent_u = Eigen::Vector3d::Zero();  // S_u [mm per unit u]
  Eigen::Vector3d tangent_v = Eigen::Vector3d::Zero();  // S_v [mm per unit v]
  /// Signed penetration depth [mm]: positive when the surface point is inside
  /// the tool, zero when touching, negative (down to -eps) when just apart.
  double depth = 0.0;
  int region = -1;  // connected contact region id
};

struct [[nodiscard]] CollisionResult {
  /// Not ok (and nothing computed) when the request is outside the documented
  /// range for the surfaces queried: see check_request().
  Status status;
  std::vector<Contact> contacts;  // grouped by region, deepest first within a region
  int region_count = 0;
  QueryCounters counters;
  /// Surface-surface queries: intersection curves, chained from the leaf
  /// triangle segments (empty for other queries).
  std::vector<IntersectionCurve> curves;
  /// Surface-surface queries given request.material_a: the contacts off the
  /// material (a crossing there has depth 0), grouped, ranked and kept to
  /// max_contacts as `contacts` are (their regions numbered apart, not
  /// refined): where the whole surface touches or crosses, for callers that
  /// move against it (a tool's advance and slide).
  std::vector<Contact> off_material;
};

/// Smallest tolerance relative to the model: below it the flatness bounds and
/// the Newton steps are rounding noise, and descents run to the deepest level.
inline constexpr double kMinRelativeTolerance = 1e-12;

/// Checks a request for a query on `surface` against the documented range
/// (docs/range.md): tolerance finite, at most the surface's size (the
/// diagonal of its control points' box) and at least kMinRelativeTolerance of
/// that size and of the coordinates' magnitude (the largest |coordinate|,
/// whose rounding no query can resolve); max_contacts >= 1; max_level in
/// [0, SurfaceHierarchy::kMaxLevel]. Every query runs it first and returns
/// its status (invalid_argument, naming the value and the limit) on failure.
/// O(1) for unchanged control points (the root block's bound is cached).
Status check_request(const CollisionRequest& request, const SurfaceHierarchy& surface);

}  // namespace argil
