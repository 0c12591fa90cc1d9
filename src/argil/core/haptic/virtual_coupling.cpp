#include "argil/core/haptic/virtual_coupling.hpp"

#include <algorithm>

#include "argil/core/base/number_text.hpp"

namespace argil {

namespace {

Status coupling_error(const char* field, double value, const Interval& range, const char* unit) {
  return Status::error(StatusCode::invalid_argument, std::string("coupling.") + field + " " +
                                                         out_of_interval_text(value, range, unit));
}

}  // namespace

Status validate(const CouplingOptions& c) {
  const CouplingRange& r = kCouplingRange;
  if (!r.stiffness.contains(c.stiffness))
    return coupling_error("stiffness", c.stiffness, r.stiffness, "N/mm");
  if (!r.damping.contains(c.damping))
    return coupling_error("damping", c.damping, r.damping, "N s/mm");
  if (!r.max_force.contains(c.max_force))
    return coupling_error("max_force", c.max_force, r.max_force, "N");
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
