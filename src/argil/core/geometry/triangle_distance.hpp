#pragma once
// Exact distances between points, segments and triangles (Ericson,
// Real-Time Collision Detection, 5.1.5 and 5.1.9), used to certify leaves.

#include <Eigen/Core>
#include <algorithm>

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

/// The same from the directions d1 = p1 - p0 and d2 = q1 - q0, their squared
/// lengths and r = p0 - q0: for callers that test each segment against
/// several others and compute those once (a triangle distance).
inline SegmentParameters closest_on_segments(const Eigen::Vector3d& d1, double d1_squared,
                                             const Eigen::Vector3d& d2, double d2_squared,
                                             const Eigen::Vector3d& r) {
  const double a = d1_squared, e = d2_squared, f = d2.dot(r);
  if (a <= 0 && e <= 0) return {};
  if (a <= 0) return {0.0, std::clamp(f / e, 0.0, 1.0)};
  const double c = d1.dot(r);
  if (e <= 0) return {std::clamp(-c / a, 0.0, 1.0), 0.0};
  const double b = d1.dot(d2);
  const double denom = a * e - b * b;
  const double s = denom > 0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
  const double t = (b * s + f) / e;
  if (t < 0) return {std::clamp(-c / a, 0.0, 1.0), 0.0};
  if (t > 1) return {std::clamp((b - c) / a, 0.0, 1.0), 1.0};
  return {s, t};
}

/// Distance between segments p0-p1 and q0-q1.
double segment_segment_distance(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                const Eigen::Vector3d& q0, const Eigen::Vector3d& q1);

/// Distance between segment p0-p1 and triangle (a, b, c); zero when they cross.
double segment_triangle_distance(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                 const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                 const Eigen::Vector3d& c);

}  // namespace argil
