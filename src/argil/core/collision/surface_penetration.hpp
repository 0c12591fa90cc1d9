#pragma once
// Penetration depth between two surfaces: how far surface b reaches behind
// surface a inside one contact region.

#include <Eigen/Core>
#include <optional>
#include <span>

#include "argil/core/collision/contact.hpp"
#include "argil/core/geometry/bspline_surface.hpp"

namespace argil {

/// The deepest point of b behind a (on the side opposite a's normal
/// S_u x S_v, which points out of a's material) near one contact region.
struct Penetration {
  double depth = 0.0;  // distance from the b point to its foot on a [mm], > 0
  Eigen::Vector2d uv_a = Eigen::Vector2d::Zero();  // the foot on a
  Eigen::Vector2d uv_b = Eigen::Vector2d::Zero();  // the deepest point of b
};

/// Searches b over the parameter box of the region's uv_b (grown by half its
/// size each way, clamped to b's domain, since the deepest point lies inside
/// the region the curve encloses), and a over the box of the region's uv_a
/// grown the same way: the deepest point of b below a's tangent plane at the
/// current foot (split into 2x2 starts), then the foot again, alternating
/// until the depth settles. A local search: exact for a planar a, and
/// converges to the deepest point where a bends less than b over the region.
/// Empty when no point of b near the region is behind a (or the region is
/// empty, or a is degenerate at the start): not an error, so no Status.
std::optional<Penetration> deepest_penetration(const BSplineSurface& a, const BSplineSurface& b,
                                               std::span<const Contact> region);

}  // namespace argil
