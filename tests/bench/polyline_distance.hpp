#pragma once
// Distance from points to a set of polylines, for coverage measures over
// hundreds of thousands of segments: segments grouped in runs with a box
// each, runs farther than the best distance so far skipped.

#include <Eigen/Core>
#include <vector>

#include "intersection_peers.hpp"

namespace argil::bench {

class PolylineDistance {
 public:
  explicit PolylineDistance(const std::vector<Polyline>& lines);
  /// Distance from p to the nearest segment (or lone point); infinity when
  /// the set is empty.
  double operator()(const Eigen::Vector3d& p) const;

 private:
  struct Run {
    const Polyline* line;
    std::size_t first, last;  // points first..last (inclusive)
    Eigen::Vector3d lo, hi;
  };
  std::vector<Run> runs_;
};

}  // namespace argil::bench
