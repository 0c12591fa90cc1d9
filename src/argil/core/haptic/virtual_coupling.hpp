#pragma once
// The virtual coupling (docs/deformation.md): a spring-damper between the haptic
// device and the tool proxy, and the one force per tick it renders.

#include <Eigen/Core>

#include "argil/core/base/number_text.hpp"
#include "argil/core/base/status.hpp"

namespace argil {

/// Spring-damper between the device and the tool proxy, and the device's force
/// limit. The scene loader reads it directly ("coupling" in a scene file);
/// these are the defaults of both.
struct CouplingOptions {
  double stiffness = 1.0;   // k [N/mm], (0, 1e6]
  double damping = 0.002;   // b [N s/mm], [0, 1e3]
  double max_force = 10.0;  // the device's maximum force [N], (0, 1e4]
};

/// Documented range of each CouplingOptions field, in the field's unit.
/// validate() and the scene reader both check against these, so they agree.
struct CouplingRange {
  Interval stiffness{0.0, 1e6, IntervalEnds::open_low};  // [N/mm]
  Interval damping{0.0, 1e3};                            // [N s/mm]
  /// [N]; the force clamp caps what a device feels.
  Interval max_force{0.0, 1e4, IntervalEnds::open_low};
};
inline constexpr CouplingRange kCouplingRange{};

/// ok, or invalid_argument naming the field outside its range.
Status validate(const CouplingOptions& coupling);

/// The coupling force on a compliant surface, solved backwards in time.
/// The proxy rests on the loaded point, so when the surface gives way by s
/// along the force direction the spring shortens by s. With f0 the explicit
/// force magnitude [N], s_free the loaded point's motion without the tool
/// [mm] and c its compliance [mm/N] (DeformableBody::begin_step), the force at
/// the end of the step is f = k (f0 / k - s_free - c f), that is
///   f = (f0 - k s_free) / (1 + k c),
/// at least 0 (a tool only pushes). A rigid surface (c = 0, s_free = 0) gives f0.
double implicit_coupling_force(double explicit_force, double stiffness, double free_motion,
                               double compliance);

/// A force limited to the device's maximum.
struct ClampedForce {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();  // [N], |force| <= max_force
  bool clamped = false;                             // the input was longer
};
/// `force` scaled to at most max_force [N] in magnitude.
ClampedForce clamp_force(const Eigen::Vector3d& force, double max_force);

}  // namespace argil
