#pragma once
// Exact distances between points, segments and triangles (Ericson,
// Real-Time Collision Detection, 5.1.5 and 5.1.9), used to certify leaves.

#include <Eigen/Core>

namespace argil {

/// Closest point of triangle (a, b, c) to p.
Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                          const Eigen::Vector3d& b, const Eigen::Vector3d& c);

/// Parameters in [0, 1] of a closest pair of points on two segments.
struct SegmentParameters {
  double s = 0.0;  // on p0 + s (p1 - p0)
  double t = 0.0;  // on q0 + t (q1 - q0)
};

/// Parameters of the closest points of segments p0-p1 and q0-q1 (Ericson
/// 5.1.9); a degenerate segment has parameter 0.
SegmentParameters closest_on_segments(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                      const Eigen::Vector3d& q0, const Eigen::Vector3d& q1);

/// Distance between segments p0-p1 and q0-q1.
double segment_segment_distance(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                const Eigen::Vector3d& q0, const Eigen::Vector3d& q1);

/// Distance between segment p0-p1 and triangle (a, b, c); zero when they cross.
double segment_triangle_distance(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                 const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                 const Eigen::Vector3d& c);

}  // namespace argil
