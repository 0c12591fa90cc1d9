#include "support/polyline_distance.hpp"

#include <algorithm>
#include <limits>

namespace argil::test {

double distance_to_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                           const Eigen::Vector3d& b) {
  const Eigen::Vector3d d = b - a;
  const double l2 = d.squaredNorm();
  const double t = l2 > 0.0 ? std::clamp((p - a).dot(d) / l2, 0.0, 1.0) : 0.0;
  return (a + t * d - p).norm();
}

double distance_to_polyline(const Eigen::Vector3d& p, const std::vector<Eigen::Vector3d>& line) {
  if (line.size() == 1) return (line[0] - p).norm();
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k + 1 < line.size(); ++k)
    best = std::min(best, distance_to_segment(p, line[k], line[k + 1]));
  return best;
}

}  // namespace argil::test
