#pragma once
// The B-spline / NURBS surface value type, its validation, and cheap structural
// queries (counts, domain, Greville abscissae, bounding box).

#include <Eigen/Core>
#include <array>
#include <string>

#include "argil/core/base/status.hpp"

namespace argil {

/// Parametric direction. Code that treats u and v alike is written once and
/// takes a Direction.
enum class Direction : int { u = 0, v = 1 };
inline constexpr std::array<Direction, 2> kDirections{Direction::u, Direction::v};
inline constexpr int index_of(Direction d) { return static_cast<int>(d); }
inline constexpr Direction other(Direction d) {
  return d == Direction::u ? Direction::v : Direction::u;
}
const char* to_string(Direction d);

/// Highest degree argil accepts in either direction (documented range).
inline constexpr int kMaxDegree = 24;

/// The rest of the documented range (docs/range.md). Inside it every
/// evaluation, bound and query result is finite with room to spare (second
/// derivatives stay below about 1e80); outside it validate() refuses.
/// Largest |coordinate| of a control point [mm] (a million kilometres).
inline constexpr double kMaxCoordinate = 1e12;
/// Largest |knot value|.
inline constexpr double kMaxKnotMagnitude = 1e12;
/// Shortest non-empty knot span relative to the domain length, and shortest
/// domain relative to max(1, largest |knot|): shorter spans are a few ulps
/// wide, their derivatives rounding noise.
inline constexpr double kMinSpanRatio = 1e-12;
/// Weights lie in [1 / kMaxWeight, kMaxWeight], and the largest is at most
/// kMaxWeightRatio times the smallest (derivative accuracy drops in
/// proportion to that ratio).
inline constexpr double kMaxWeight = 1e12;
inline constexpr double kMaxWeightRatio = 1e8;

/// A tensor-product B-spline surface, rational when `weights` is non-empty.
///
/// S(u, v) = sum_ij N_i,p(u) N_j,q(v) w_ij P_ij / sum_ij N_i,p(u) N_j,q(v) w_ij
///
/// - `degree[d]` >= 1, `knots[d]` clamped (first and last values repeated
///   degree+1 times) and non-decreasing; interior multiplicity at most degree.
/// - The number of control points in direction d is knots[d].size() - degree[d] - 1.
/// - `control_points` is (n_u * n_v) x 3 [mm], row `i * n_v + j` for pole (i, j).
/// - `weights` is empty (polynomial) or has n_u * n_v positive entries, same order.
/// A plain value: copy it, compare it, change its control points freely; call
/// validate() before trusting data from outside.
struct BSplineSurface {
  std::array<int, 2> degree{1, 1};
  std::array<Eigen::VectorXd, 2> knots;
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> control_points;
  Eigen::VectorXd weights;

  int degree_in(Direction d) const { return degree[index_of(d)]; }
  const Eigen::VectorXd& knots_in(Direction d) const { return knots[index_of(d)]; }
  /// Number of control points in direction d (from the knot count).
  int count(Direction d) const { return static_cast<int>(knots_in(d).size()) - degree_in(d) - 1; }
  /// Row of pole (i, j) in `control_points` and `weights`.
  Eigen::Index pole_index(int i, int j) const {
    return static_cast<Eigen::Index>(i) * count(Direction::v) + j;
  }
  bool is_rational() const { return weights.size() > 0; }
  /// Parameter interval [first, last] in direction d.
  double domain_start(Direction d) const { return knots_in(d)[degree_in(d)]; }
  double domain_end(Direction d) const { return knots_in(d)[count(d)]; }
};

using ControlNet = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

/// Checks every invariant listed on BSplineSurface, in a fixed order (degrees,
/// knots of u then v, control points, weights), and reports the first one
/// broken: invalid_surface with a message naming the field, index and value
/// ("knots_u[5] is nan"). Never evaluates the surface.
Status validate(const BSplineSurface& surface);

/// Greville abscissae in direction d: xi_i = (t_{i+1} + ... + t_{i+p}) / p,
/// one per control point, non-decreasing, first and last on the domain ends.
Eigen::VectorXd greville_abscissae(int degree, const Eigen::VectorXd& knots);

/// Axis-aligned box of the control points. It encloses the surface (convex hull
/// property, positive weights); it is not tight.
struct Box3 {
  Eigen::Vector3d min;
  Eigen::Vector3d max;
  Eigen::Vector3d extent() const { return max - min; }
  /// Length of the diagonal [mm]: the model size that tolerances scale with.
  double diagonal() const { return extent().norm(); }
};
Box3 control_point_box(const BSplineSurface& surface);

/// Homogeneous control points (w x, w y, w z, w), one row per pole; w = 1 when
/// the surface is polynomial.
Eigen::MatrixX4d homogeneous_control_points(const BSplineSurface& surface);

/// `surface` with its control points (and weights when `rational`, none
/// otherwise) taken from homogeneous rows; degrees and knots are kept.
BSplineSurface with_homogeneous_control_points(BSplineSurface surface, const Eigen::MatrixX4d& pw,
                                               bool rational);

}  // namespace argil
