#pragma once
// Whether a moving leaf meets a fixed one at some time of its motion: the
// leaf step of the swept surface-surface query (collide_swept). A flat leaf is
// its two corner triangles; every corner moves on a straight line.

#include <Eigen/Core>
#include <array>
#include <optional>

#include "argil/core/collision/triangle_intersection.hpp"

namespace argil::detail {

/// A leaf's corners S(0,0), S(1,0), S(0,1), S(1,1); its triangles are
/// (c00, c10, c11) and (c00, c11, c01), the split of the hierarchy's bounds.
using LeafCorners = std::array<Eigen::Vector3d, 4>;

/// The leaf's two triangles.
std::array<Triangle, 2> leaf_triangles_of(const LeafCorners& c);

/// Where a fixed leaf was met: a point on it, its triangle (0 or 1) and its
/// barycentric coordinates there; and the point of the moving leaf that met
/// it, as its triangle and barycentric coordinates.
struct SweptHit {
  Eigen::Vector3d point;
  int triangle = 0;
  Eigen::Vector3d bary;
  int triangle_b = 0;
  Eigen::Vector3d bary_b;
};

/// The fixed leaf `a` and the moving leaf b: b's corners at the motion's start
/// and end in a's frame, and (for the same motion seen from b) a's corners in
/// b's own frame at the start and end, with b's own corners there.
struct SweptLeafPair {
  LeafCorners a;
  LeafCorners b_start, b_end;
  LeafCorners a_in_b_start, a_in_b_end;
  LeafCorners b_own;
};

/// A hit when some triangle of b meets some triangle of a during the motion
/// (touching counts): a corner of b passes through a, an edge of b sweeps
/// across an edge of a, or (seen from b) a corner of a passes through b.
/// Those are the ways two triangles that do not meet at the start first meet.
/// A pair is skipped when b's triangle stays strictly on one side of a's plane
/// at both ends (so, its corners moving on lines, throughout), or a's on one
/// side of b's in b's frame. For a translation both views are exact; with a
/// rotation each is the straight-line model of the corners' arcs.
std::optional<SweptHit> swept_leaves_meet(const SweptLeafPair& pair);

}  // namespace argil::detail
