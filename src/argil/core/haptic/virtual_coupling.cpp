#include "argil/core/haptic/virtual_coupling.hpp"

#include <algorithm>
#include <sstream>

namespace argil {

namespace {

Status coupling_error(const char* field, double value, const char* range) {
  std::ostringstream m;
  m.precision(17);
  m << "coupling." << field << " = " << value << " is outside " << range;
  return Status::error(StatusCode::invalid_argument, m.str());
}

}  // namespace

Status validate(const CouplingOptions& c) {
  if (!(c.stiffness > 0.0 && c.stiffness <= 1e6))
    return coupling_error("stiffness", c.stiffness, "(0, 1e6] N/mm");
  if (!(c.damping >= 0.0 && c.damping <= 1e3))
    return coupling_error("damping", c.damping, "[0, 1e3] N s/mm");
  if (!(c.max_force > 0.0 && c.max_force <= 1e4))
    return coupling_error("max_force", c.max_force, "(0, 1e4] N");
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
