#include "argil/core/haptic/virtual_coupling.hpp"

#include <algorithm>

#include "argil/core/base/number_text.hpp"

namespace argil {

namespace {

// Bounds of the coupling parameters; the force clamp caps what a device feels.
constexpr Interval kStiffnessRange{0.0, 1e6, IntervalEnds::open_low};  // [N/mm]
constexpr Interval kDampingRange{0.0, 1e3};                            // [N s/mm]
constexpr Interval kMaxForceRange{0.0, 1e4, IntervalEnds::open_low};   // [N]

Status coupling_error(const char* field, double value, const Interval& range, const char* unit) {
  return Status::error(StatusCode::invalid_argument, std::string("coupling.") + field + " " +
                                                         out_of_interval_text(value, range, unit));
}

}  // namespace

Status validate(const CouplingOptions& c) {
  if (!kStiffnessRange.contains(c.stiffness))
    return coupling_error("stiffness", c.stiffness, kStiffnessRange, "N/mm");
  if (!kDampingRange.contains(c.damping))
    return coupling_error("damping", c.damping, kDampingRange, "N s/mm");
  if (!kMaxForceRange.contains(c.max_force))
    return coupling_error("max_force", c.max_force, kMaxForceRange, "N");
  return Status::success();
}

double implicit_coupling_force(double explicit_force, double stiffness, double free_motion,
                               double compliance) {
  return std::max(0.0, (explicit_force - stiffness * free_motion) / (1.0 + stiffness * compliance));
}

ClampedForce clamp_force(const Eigen::Vector3d& force, double max_force) {
  const double size = force.norm();
  if (!(size > max_force)) return {force, false};
  return {force * (max_force / size), true};
}

}  // namespace argil
