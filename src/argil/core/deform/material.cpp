#include "argil/core/deform/material.hpp"

#include <string>

#include "argil/core/base/number_text.hpp"

namespace argil {

namespace {

/// Error naming `field`, its range and the value, both in `unit` (the unit
/// scene files give the field in).
Status out_of_range(const char* field, double value, const Interval& range, const char* unit) {
  return Status::error(StatusCode::invalid_argument, std::string("material.") + field + " " +
                                                         out_of_interval_text(value, range, unit));
}

/// A layer of `thickness` [mm] of a solid with modulus E [MPa] on a rigid core
/// pushes back with E / thickness per mm of displacement: the foundation of
/// the soft presets.
constexpr double layer_foundation(double youngs_modulus, double thickness) {
  return youngs_modulus / thickness;
}

}  // namespace

ShellStiffness shell_stiffness(const Material& m) {
  const double plane = 1.0 - m.poisson_ratio * m.poisson_ratio;
  const double h = m.thickness;
  return {.membrane = m.youngs_modulus * h / plane,
          .bending = m.youngs_modulus * h * h * h / (12.0 * plane),
          .foundation = m.foundation_stiffness,
          .mass_per_area = m.density * kKgPerM3ToKgPerMm3 * h};
}

Status validate(const Material& m) {
  const MaterialRange& r = kMaterialRange;
  if (!r.density.contains(m.density))
    return out_of_range("density", m.density, r.density, "kg/m^3");
  if (!r.thickness.contains(m.thickness))
    return out_of_range("thickness", m.thickness, r.thickness, "mm");
  if (!r.youngs_modulus.contains(m.youngs_modulus))
    return out_of_range("youngs_modulus", m.youngs_modulus, r.youngs_modulus, "MPa");
  if (!r.poisson_ratio.contains(m.poisson_ratio))
    return out_of_range("poisson_ratio", m.poisson_ratio, r.poisson_ratio, "");
  if (!r.foundation_stiffness.contains(m.foundation_stiffness))
    return out_of_range("foundation_stiffness", m.foundation_stiffness, r.foundation_stiffness,
                        "N/mm^3");
  if (!r.damping.contains(m.damping)) return out_of_range("damping", m.damping, r.damping, "s");
  if (!r.yield.contains(m.yield)) return out_of_range("yield", m.yield, r.yield, "mm");
  return Status::success();
}

const std::vector<MaterialPreset>& material_presets() {
  constexpr double elastic = std::numeric_limits<double>::infinity();
  static const std::vector<MaterialPreset> presets = {
      {"clay",
       "industrial design clay, a 5 mm layer on a rigid core; keeps dents",
       {.density = 1700,
        .thickness = 5,
        .youngs_modulus = 0.5,
        .poisson_ratio = 0.45,
        .foundation_stiffness = layer_foundation(0.5, 5),
        .damping = 1e-3,
        .yield = 0.02}},
      {"wax",
       "modelling wax, a 3 mm layer on a rigid core; stiff, keeps dents",
       {.density = 950,
        .thickness = 3,
        .youngs_modulus = 50,
        .poisson_ratio = 0.4,
        .foundation_stiffness = layer_foundation(50, 3),
        .damping = 1e-3,
        .yield = 0.005}},
      {"foam",
       "soft polyurethane foam, a 10 mm layer; elastic, springs back",
       {.density = 30,
        .thickness = 10,
        .youngs_modulus = 0.05,
        .poisson_ratio = 0.3,
        .foundation_stiffness = layer_foundation(0.05, 10),
        .damping = 1e-3,
        .yield = elastic}},
      {"sheet_steel",
       "1 mm steel sheet on a stiff backing; elastic",
       {.density = 7850,
        .thickness = 1,
        .youngs_modulus = 210000,
        .poisson_ratio = 0.3,
        .foundation_stiffness = 10,
        .damping = 1e-3,
        .yield = elastic}},
      {"aluminium",
       "1 mm aluminium sheet on a stiff backing; elastic",
       {.density = 2700,
        .thickness = 1,
        .youngs_modulus = 70000,
        .poisson_ratio = 0.33,
        .foundation_stiffness = 10,
        .damping = 1e-3,
        .yield = elastic}},
      {"abs",
       "2 mm ABS plastic shell on a stiff backing; elastic",
       {.density = 1040,
        .thickness = 2,
        .youngs_modulus = 2300,
        .poisson_ratio = 0.35,
        .foundation_stiffness = 10,
        .damping = 1e-3,
        .yield = elastic}},
  };
  return presets;
}

std::optional<Material> material_preset(std::string_view name) {
  for (const MaterialPreset& p : material_presets())
    if (p.name == name) return p.material;
  return std::nullopt;
}

}  // namespace argil
