#include "argil/core/deform/material.hpp"

#include "argil/core/base/number_text.hpp"

namespace argil {

namespace {

/// Error naming `field`, its range and the value, both in `unit` (the unit
/// scene files give the field in).
Status out_of_range(const char* field, double value, const Interval& range, const char* unit) {
  return Status::error(StatusCode::invalid_argument, std::string("material.") + field + " " +
                                                         out_of_interval_text(value, range, unit));
}

}  // namespace

Status validate(const Material& m) {
  const MaterialRange& r = kMaterialRange;
  if (!r.density.contains(m.density))
    return out_of_range("density", m.density, r.density, "kg/mm^2");
  if (!r.stiffness.contains(m.stiffness))
    return out_of_range("stiffness", m.stiffness, r.stiffness, "N/mm");
  if (!r.damping.contains(m.damping)) return out_of_range("damping", m.damping, r.damping, "s");
  if (!r.anchor_stiffness.contains(m.anchor_stiffness))
    return out_of_range("anchor_stiffness", m.anchor_stiffness, r.anchor_stiffness, "N/mm");
  if (!r.yield.contains(m.yield)) return out_of_range("yield", m.yield, r.yield, "mm");
  return Status::success();
}

}  // namespace argil
