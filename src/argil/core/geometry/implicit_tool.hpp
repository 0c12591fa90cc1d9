#pragma once
// Implicit tools: shapes given by a signed distance (negative inside) with a
// known Lipschitz bound, so a node's sphere gives a certified lower bound.

#include <Eigen/Core>
#include <functional>
#include <memory>

#include "argil/core/geometry/bspline_surface.hpp"

namespace argil {

/// Distance value, gradient and Hessian at a point (world frame, [mm]).
struct DistanceSample {
  double value = 0.0;
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
  Eigen::Matrix3d hessian = Eigen::Matrix3d::Zero();
};

/// A tool shape in the world frame W. `distance` is a signed distance (or a
/// function with the same zero set and sign) that changes by at most
/// lipschitz() per mm, so |f(x) - f(c)| <= L |x - c| bounds it on a sphere.
class ImplicitTool {
 public:
  virtual ~ImplicitTool() = default;
  virtual DistanceSample distance(const Eigen::Vector3d& p_W) const = 0;
  /// The function value alone (no derivatives): what pruning needs.
  virtual double value(const Eigen::Vector3d& p_W) const { return distance(p_W).value; }
  virtual double lipschitz() const { return 1.0; }
  /// A lower bound of the function over triangle (a, b, c). Plane, sphere and
  /// capsule give the exact minimum; others f(centroid) - L * circumradius.
  virtual double lower_bound_on_triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                         const Eigen::Vector3d& c) const;
  /// True when lower_bound_on_triangle is exact, so leaves are certified
  /// without descending to nodes smaller than eps.
  virtual bool exact_triangle_bound() const { return false; }
  /// A box [mm] that holds every point where the function is <= 0 (the tool's
  /// solid), for the broad phase. Unbounded tools (plane, user SDF) return an
  /// infinite box, so they pair with every surface.
  virtual Box3 bounding_box() const;
};

/// Half-space n . x <= offset (n unit): the inside is below the plane.
std::unique_ptr<ImplicitTool> make_plane(const Eigen::Vector3d& normal_W, double offset);
/// Ball of `radius` [mm] around p_WC.
std::unique_ptr<ImplicitTool> make_sphere(const Eigen::Vector3d& p_WC, double radius);
/// Points within `radius` of the segment a-b.
std::unique_ptr<ImplicitTool> make_capsule(const Eigen::Vector3d& a_W, const Eigen::Vector3d& b_W,
                                           double radius);
/// Axis-aligned box (in the tool frame) of half extents, posed by rotation R_WT and centre.
std::unique_ptr<ImplicitTool> make_box(const Eigen::Matrix3d& R_WT, const Eigen::Vector3d& p_WT,
                                       const Eigen::Vector3d& half_extents);
/// Ellipsoid with semi-axes `radii` along the tool frame axes. Its function is
/// (|x / radii| - 1) * min(radii): exact zero set, 1-Lipschitz, and a lower
/// bound on the Euclidean distance outside (depth is approximate inside).
std::unique_ptr<ImplicitTool> make_ellipsoid(const Eigen::Matrix3d& R_WT,
                                             const Eigen::Vector3d& p_WT,
                                             const Eigen::Vector3d& radii);
/// Torus around the tool z axis: ring radius `major`, tube radius `minor`.
std::unique_ptr<ImplicitTool> make_torus(const Eigen::Matrix3d& R_WT, const Eigen::Vector3d& p_WT,
                                         double major, double minor);
/// A user signed distance with Lipschitz bound L (>= its true rate of change);
/// gradient and Hessian by central differences with step h [mm].
std::unique_ptr<ImplicitTool> make_user_sdf(std::function<double(const Eigen::Vector3d&)> f,
                                            double lipschitz, double h = 1e-4);

}  // namespace argil
