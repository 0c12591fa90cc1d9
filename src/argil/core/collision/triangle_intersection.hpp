#pragma once
// Triangle against triangle: the intersection segment (Moller 1997, "A fast
// triangle-triangle intersection test", with filtered orientation predicates)
// and the closest points of two disjoint triangles. The leaf step of the
// surface-surface descent.

#include <Eigen/Core>
#include <array>

namespace argil {

/// Corners of a triangle [mm].
using Triangle = std::array<Eigen::Vector3d, 3>;

/// Sign of the volume of (a, b, c, d): +1 when d lies on the side of plane
/// (a, b, c) that (b - a) x (c - a) points to, -1 on the other, 0 when |det|
/// is within Shewchuk's forward error bound of the double evaluation (the sign
/// is then not certain and the point counts as on the plane). The same
/// quadruple always gives the same answer, so every decision built from it is
/// consistent; `value` is the determinant, zeroed when the sign is 0.
struct Orientation {
  int sign = 0;
  double value = 0.0;
};
Orientation orient3d(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                     const Eigen::Vector3d& d);

/// What two triangles share.
struct TriangleIntersection {
  enum class Kind {
    none,      // disjoint (up to the predicates' certainty)
    segment,   // the planes cross; the triangles share points[0]..points[1]
               // (equal points when they touch at one point)
    coplanar,  // every corner lies on the other plane and the triangles
               // overlap; points[0] = points[1] = centroid of the overlap polygon
  };
  Kind kind = Kind::none;
  std::array<Eigen::Vector3d, 2> points{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  /// Barycentric coordinates (sum 1, non-negative) of each point on triangle a
  /// and on triangle b, so callers can map the points to their own parameters.
  std::array<Eigen::Vector3d, 2> bary_a{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  std::array<Eigen::Vector3d, 2> bary_b{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
};

/// Intersection of triangles a and b. Each corner's side of the other plane is
/// decided once by orient3d; the crossing segment of each triangle with the
/// other's plane is interpolated from those determinants, and the two segments
/// are clipped against each other along the planes' common line. Touching
/// (a corner or edge on the other triangle) counts as intersecting when the
/// predicates certify it; degenerate (zero-area) triangles give `none` unless
/// another triangle crosses them through the segment path.
///
/// A corner within `on_plane` [mm] of the other triangle's plane counts as on
/// it. Corners evaluated on a surface carry its rounding: a face's boundary
/// that lies in a neighbour's plane (a shared CAD edge) falls on either side
/// of it by a few ulps, and would give a touch on one side and nothing on the
/// other instead of the segment along the edge.
TriangleIntersection intersect_triangles(const Triangle& a, const Triangle& b,
                                         double on_plane = 0.0);

/// Closest points of two triangles (15 feature pairs: 6 corner-face, 9
/// edge-edge; Ericson, Real-Time Collision Detection 5.1.5 and 5.1.9).
/// Intended for disjoint triangles: when they cross the distance is still a
/// minimum over those features, which is zero only when a feature touches.
struct TriangleDistance {
  double distance = 0.0;  // [mm]
  Eigen::Vector3d point_a = Eigen::Vector3d::Zero();
  Eigen::Vector3d point_b = Eigen::Vector3d::Zero();
  Eigen::Vector3d bary_a = Eigen::Vector3d::Zero();
  Eigen::Vector3d bary_b = Eigen::Vector3d::Zero();
};
TriangleDistance triangle_distance(const Triangle& a, const Triangle& b);

/// Barycentric coordinates of p projected onto the plane of (a, b, c),
/// clamped to the triangle (non-negative, sum 1). Degenerate triangles give
/// the coordinates of the nearest corner.
Eigen::Vector3d barycentric(const Eigen::Vector3d& p, const Triangle& t);

}  // namespace argil
