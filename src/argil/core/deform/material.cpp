#include "argil/core/deform/material.hpp"

#include <cmath>

#include "argil/core/base/number_text.hpp"

namespace argil {

namespace {

/// Error naming `field`, the range [low, high] and the value, both in `unit`
/// (the unit scene files give the field in).
Status out_of_range(const char* field, double value, double low, double high, const char* unit) {
  return Status::error(
      StatusCode::invalid_argument,
      std::string("material.") + field + " " + out_of_interval_text(value, {low, high}, unit));
}

bool within(double value, double low, double high) { return value >= low && value <= high; }

}  // namespace

Status validate(const Material& m) {
  const MaterialRange& r = kMaterialRange;
  if (!within(m.density, r.density_min, r.density_max))
    return out_of_range("density", m.density, r.density_min, r.density_max, "kg/mm^2");
  if (!within(m.stiffness, 0.0, r.stiffness_max))
    return out_of_range("stiffness", m.stiffness, 0.0, r.stiffness_max, "N/mm");
  if (!within(m.damping, 0.0, r.damping_max))
    return out_of_range("damping", m.damping, 0.0, r.damping_max, "s");
  if (!within(m.anchor_stiffness, 0.0, r.anchor_stiffness_max))
    return out_of_range("anchor_stiffness", m.anchor_stiffness, 0.0, r.anchor_stiffness_max,
                        "N/mm");
  if (!(m.yield >= r.yield_min))  // +infinity is valid (elastic); NaN is not
    return out_of_range("yield", m.yield, r.yield_min, std::numeric_limits<double>::infinity(),
                        "mm");
  return Status::success();
}

}  // namespace argil
