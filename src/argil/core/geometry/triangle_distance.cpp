#include "argil/core/geometry/triangle_distance.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace argil {

Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                          const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  }
  const double sum = va + vb + vc;
  if (!(sum > 0)) {  // degenerate (collinear) triangle: nearest of its edges
    const auto on_segment = [&p](const Eigen::Vector3d& s, const Eigen::Vector3d& t) {
      const Eigen::Vector3d st = t - s;
      const double l2 = st.squaredNorm();
      const double x = l2 > 0 ? std::clamp((p - s).dot(st) / l2, 0.0, 1.0) : 0.0;
      return Eigen::Vector3d(s + x * st);
    };
    Eigen::Vector3d best = on_segment(a, b);
    for (const Eigen::Vector3d& q : {on_segment(b, c), on_segment(c, a)})
      if ((q - p).squaredNorm() < (best - p).squaredNorm()) best = q;
    return best;
  }
  const double denom = 1.0 / sum;
  return a + ab * (vb * denom) + ac * (vc * denom);
}

SegmentParameters closest_on_segments(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                      const Eigen::Vector3d& q0, const Eigen::Vector3d& q1) {
  const Eigen::Vector3d d1 = p1 - p0, d2 = q1 - q0;
  return closest_on_segments(d1, d1.squaredNorm(), d2, d2.squaredNorm(), p0 - q0);
}

double segment_segment_distance(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                const Eigen::Vector3d& q0, const Eigen::Vector3d& q1) {
  const auto [s, t] = closest_on_segments(p0, p1, q0, q1);
  return ((p0 + (p1 - p0) * s) - (q0 + (q1 - q0) * t)).norm();
}

double segment_triangle_distance(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                 const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                 const Eigen::Vector3d& c) {
  // Crossing: the segment's end points lie on opposite sides of the plane and
  // the crossing point is inside the triangle.
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const double s0 = n.dot(p0 - a), s1 = n.dot(p1 - a);
  if (s0 * s1 <= 0 && s0 != s1) {
    const Eigen::Vector3d x = p0 + (p1 - p0) * (s0 / (s0 - s1));
    if ((closest_point_on_triangle(x, a, b, c) - x).norm() <= 0.0) return 0.0;
  }
  double best = std::min((closest_point_on_triangle(p0, a, b, c) - p0).norm(),
                         (closest_point_on_triangle(p1, a, b, c) - p1).norm());
  best = std::min(best, segment_segment_distance(p0, p1, a, b));
  best = std::min(best, segment_segment_distance(p0, p1, b, c));
  best = std::min(best, segment_segment_distance(p0, p1, c, a));
  return best;
}

}  // namespace argil
