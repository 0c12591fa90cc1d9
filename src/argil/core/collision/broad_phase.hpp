#pragma once
// Broad phase across the bodies of a scene: which pairs of conservative boxes
// come within eps of each other, by sweep and prune.

#include <vector>

#include "argil/core/geometry/bspline_surface.hpp"

namespace argil {

/// Indices of two bodies, a < b.
struct BodyPair {
  int a = 0;
  int b = 0;
  friend bool operator==(const BodyPair&, const BodyPair&) = default;
};

/// Every pair (a, b), a < b, whose boxes are at most `eps` apart along every
/// axis (touching within eps counts), sorted by (a, b). Boxes may be infinite
/// in any direction (an unbounded tool): they are compared like any other.
/// Sweep and prune along the axis where the box centres spread the most;
/// O(n log n + k) for k overlaps along that axis. A box with a NaN bound is a
/// caller error: it pairs with nothing.
std::vector<BodyPair> overlapping_pairs(const std::vector<Box3>& boxes, double eps);

}  // namespace argil
