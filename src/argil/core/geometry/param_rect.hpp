#pragma once
// A rectangle [u0, u1] x [v0, v1] in a surface's parameter space: the domain
// of a hierarchy node, a leaf, a search box or a tessellation cell.

#include <Eigen/Core>
#include <algorithm>
#include <array>

#include "argil/core/geometry/bspline_surface.hpp"

namespace argil {

/// Closed parameter rectangle. Degenerate (zero-width) rectangles are allowed;
/// callers that divide by a side check it first.
struct ParamRect {
  double u0 = 0.0, u1 = 0.0, v0 = 0.0, v1 = 0.0;

  double start(Direction d) const { return d == Direction::u ? u0 : v0; }
  double end(Direction d) const { return d == Direction::u ? u1 : v1; }
  /// Side length in direction d.
  double extent(Direction d) const { return end(d) - start(d); }
  double width() const { return u1 - u0; }   // extent in u
  double height() const { return v1 - v0; }  // extent in v
  double min_side() const { return std::min(width(), height()); }
  Eigen::Vector2d lower() const { return {u0, v0}; }
  Eigen::Vector2d upper() const { return {u1, v1}; }
  Eigen::Vector2d centre() const { return {0.5 * (u0 + u1), 0.5 * (v0 + v1)}; }
  /// Corner k in the order (u0,v0), (u1,v0), (u0,v1), (u1,v1), the order of
  /// PatchBound::corners.
  Eigen::Vector2d corner(int k) const { return {k % 2 == 0 ? u0 : u1, k < 2 ? v0 : v1}; }
  /// True when uv lies in the closed rectangle.
  bool contains(const Eigen::Vector2d& uv) const {
    return u0 <= uv[0] && uv[0] <= u1 && v0 <= uv[1] && uv[1] <= v1;
  }
  /// True when the closed rectangles share a point (an edge or a corner counts).
  bool touches(const ParamRect& o) const {
    return u0 <= o.u1 && o.u0 <= u1 && v0 <= o.v1 && o.v0 <= v1;
  }
  /// The quarter (half_u, half_v), each 0 (lower half) or 1 (upper half).
  ParamRect quarter(int half_u, int half_v) const {
    const Eigen::Vector2d m = centre();
    return {half_u == 0 ? u0 : m[0], half_u == 0 ? m[0] : u1, half_v == 0 ? v0 : m[1],
            half_v == 0 ? m[1] : v1};
  }
  /// The four quarters in the order of corner(): (0,0), (1,0), (0,1), (1,1).
  std::array<ParamRect, 4> split() const {
    return {quarter(0, 0), quarter(1, 0), quarter(0, 1), quarter(1, 1)};
  }
  /// The rectangle with lower corner `lo` and upper corner `hi`.
  static ParamRect from_corners(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) {
    return {lo[0], hi[0], lo[1], hi[1]};
  }
  bool operator==(const ParamRect&) const = default;
};

/// The parameter domain of the surface.
inline ParamRect domain_of(const BSplineSurface& s) {
  return {s.domain_start(Direction::u), s.domain_end(Direction::u), s.domain_start(Direction::v),
          s.domain_end(Direction::v)};
}

}  // namespace argil
