#include "argil/core/collision/broad_phase.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace argil {

namespace {

bool overlap(const Box3& a, const Box3& b, double eps) {
  return (a.min.array() <= b.max.array() + eps).all() &&
         (b.min.array() <= a.max.array() + eps).all();
}

/// The axis along which the finite box centres spread the most: sweeping
/// there leaves the fewest false overlaps. Infinite boxes do not vote.
int sweep_axis(const std::vector<Box3>& boxes) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (const Box3& box : boxes) {
    const Eigen::Vector3d centre = 0.5 * (box.min + box.max);
    if (!centre.allFinite()) continue;
    lo = lo.cwiseMin(centre);
    hi = hi.cwiseMax(centre);
  }
  int axis = 0;
  (hi - lo).maxCoeff(&axis);
  return axis;
}

}  // namespace

std::vector<BodyPair> overlapping_pairs(const std::vector<Box3>& boxes, double eps) {
  std::vector<BodyPair> pairs;
  if (boxes.size() < 2) return pairs;
  const int axis = sweep_axis(boxes);

  std::vector<int> order;
  order.reserve(boxes.size());
  for (int i = 0; i < static_cast<int>(boxes.size()); ++i) {
    const Box3& box = boxes[static_cast<std::size_t>(i)];
    if (!box.min.hasNaN() && !box.max.hasNaN()) order.push_back(i);
  }
  // Ties broken by index so the pair list never depends on the sort.
  std::sort(order.begin(), order.end(), [&](int i, int j) {
    const double mi = boxes[static_cast<std::size_t>(i)].min[axis];
    const double mj = boxes[static_cast<std::size_t>(j)].min[axis];
    return mi < mj || (mi == mj && i < j);
  });

  // Sweep: a box stays active while a later box can still start within eps of its end.
  std::vector<int> active;
  for (const int j : order) {
    const Box3& next = boxes[static_cast<std::size_t>(j)];
    std::erase_if(active, [&](int i) {
      return boxes[static_cast<std::size_t>(i)].max[axis] + eps < next.min[axis];
    });
    for (const int i : active) {
      if (overlap(boxes[static_cast<std::size_t>(i)], next, eps)) {
        pairs.push_back({std::min(i, j), std::max(i, j)});
      }
    }
    active.push_back(j);
  }
  std::sort(pairs.begin(), pairs.end(), [](const BodyPair& p, const BodyPair& q) {
    return p.a < q.a || (p.a == q.a && p.b < q.b);
  });
  return pairs;
}

}  // namespace argil
