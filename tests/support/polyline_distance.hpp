#pragma once
// The distance from a point to a polyline, for tests that check reported
// curves against points (and points against reported curves).

#include <Eigen/Core>
#include <vector>

namespace argil::test {

/// The distance from p to the segment from a to b (to a when b == a).
double distance_to_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                           const Eigen::Vector3d& b);

/// The distance from p to a polyline: its segments, or its one point
/// (infinity when it has none).
double distance_to_polyline(const Eigen::Vector3d& p, const std::vector<Eigen::Vector3d>& line);

}  // namespace argil::test
