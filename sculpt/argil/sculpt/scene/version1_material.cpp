#include "argil/sculpt/scene/version1_material.hpp"

#include <algorithm>
#include <string>

namespace argil::sculpt {
namespace {

Status invalid(const std::string& message) {
  return Status::error(StatusCode::invalid_argument, message);
}

/// The first version-1 field outside kVersion1MaterialRange, named as a scene names it.
Status validate_version1(const Version1Material& old) {
  const Version1MaterialRange& r = kVersion1MaterialRange;
  const struct {
    const char* name;
    double value;
    const Interval& range;
    const char* unit;
  } fields[] = {{"density", old.density, r.density, "kg/mm^2"},
                {"stiffness", old.stiffness, r.stiffness, "N/mm"},
                {"damping", old.damping, r.damping, "s"},
                {"anchor_stiffness", old.anchor_stiffness, r.anchor_stiffness, "N/mm"},
                {"yield", old.yield, r.yield, "mm"}};
  for (const auto& f : fields) {
    if (!f.range.contains(f.value)) {
      return invalid(std::string(f.name) + " " + out_of_interval_text(f.value, f.range, f.unit));
    }
  }
  return Status::success();
}

}  // namespace

Result<Material> material_from_version1(const Version1Material& old) {
  if (const Status valid = validate_version1(old); !valid.ok()) return valid;
  const MaterialRange& r = kMaterialRange;
  const double per_mm3 = kKgPerM3ToKgPerMm3;
  // Thicknesses that keep density = areal / h inside its range...
  double thinnest = std::max(r.thickness.low, old.density / (r.density.high * per_mm3));
  const double thickest = std::min(r.thickness.high, old.density / (r.density.low * per_mm3));
  if (thinnest > thickest) {
    const Interval areal{r.density.low * per_mm3 * r.thickness.low,
                         r.density.high * per_mm3 * r.thickness.high};
    return invalid("density " + number_text(old.density) +
                   " kg/mm^2 has no physical counterpart: density x thickness spans [" +
                   approx_text(areal.low) + ", " + approx_text(areal.high) + "] kg/mm^2");
  }
  // ... and youngs_modulus = stiffness / h below its upper end.
  thinnest = std::max(thinnest, old.stiffness / r.youngs_modulus.high);
  if (thinnest > thickest) {
    return invalid("stiffness " + number_text(old.stiffness) + " N/mm with density " +
                   number_text(old.density) +
                   " kg/mm^2 has no physical counterpart: youngs_modulus = stiffness / "
                   "thickness needs a thickness of at least " +
                   limit_text(thinnest, LimitSide::lower) + " mm, where the density falls below " +
                   number_text(r.density.low) + " kg/m^3");
  }
  Material m;
  m.thickness = std::clamp(kVersion1Thickness, thinnest, thickest);
  // The clamps only undo rounding: the thickness keeps both inside mathematically.
  m.density = std::clamp(old.density / (m.thickness * per_mm3), r.density.low, r.density.high);
  m.poisson_ratio = 0.0;
  m.youngs_modulus = std::min(old.stiffness / m.thickness, r.youngs_modulus.high);
  m.foundation_stiffness = old.anchor_stiffness / kVersion1AnchorArea;
  m.damping = old.damping;
  m.yield = old.yield;
  if (const Status valid = validate(m); !valid.ok()) return valid;
  return m;
}

}  // namespace argil::sculpt
