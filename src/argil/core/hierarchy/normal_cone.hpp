#pragma once
// A cone around every normal direction of a polynomial Bezier patch, from its
// control points alone: what lets a surface-surface query prove that two
// patches cross at an angle everywhere (no tangency, no closed loop inside).

#include <Eigen/Core>
#include <optional>

#include "argil/core/geometry/bezier.hpp"

namespace argil {

/// Every normal S_s x S_t of the patch points within `half_angle` of `axis`,
/// and none is zero.
struct NormalCone {
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  // unit
  double half_angle = 0.0;                          // [rad], below pi/2
};

/// Highest degree normal_cone() bounds: the normal's Bezier net has
/// p (q + 1) (p + 1) q cross products, 8,100 at degree 9.
inline constexpr int kMaxNormalConeDegree = 9;

/// The normal S_s x S_t of a degree (p, q) patch is a Bezier patch of degree
/// (2p - 1, 2q - 1) whose control vectors are positive combinations of the
/// cross products of the net's u and v differences (Bernstein products), so
/// every normal is a positive combination of those control vectors and lies
/// in any cone around them. nullopt when no cone narrower than a half space
/// holds them, when one of them is zero (the normal may vanish: a collapsed
/// edge or corner), for rational patches (weights not all equal) and above
/// kMaxNormalConeDegree.
std::optional<NormalCone> normal_cone(const BezierPatch& patch);

/// The smallest angle [rad] between the lines of any normal in `a` and any
/// in `b` (0 when the cones reach parallel or opposite directions): where
/// two patches meet at least at this angle everywhere, their intersection
/// has no closed loop and no tangency (Sederberg and Meyers 1988).
double least_crossing_angle(const NormalCone& a, const NormalCone& b);

}  // namespace argil
