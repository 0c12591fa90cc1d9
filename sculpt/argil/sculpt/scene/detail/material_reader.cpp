#include "argil/sculpt/scene/detail/material_reader.hpp"

#include <limits>
#include <optional>

#include "argil/core/base/number_text.hpp"
#include "argil/sculpt/scene/version1_material.hpp"

namespace argil::sculpt::internal {
namespace {

/// A number field of a material and the range its validator uses.
struct RangedField {
  const char* key;
  double* value;
  const Interval& range;
  const char* unit;
};

/// "yield" at `path`: a length in `range`, or "none" (JSON has no infinity)
/// for a purely elastic material.
bool read_yield(JsonReader& r, const Json& value, const std::string& path, const Interval& range,
                double& out) {
  if (value.is_string() && value.get<std::string>() == "none") {
    out = std::numeric_limits<double>::infinity();
    return true;
  }
  return r.within(value, path, out, range, "mm");
}

/// The preset named by the string `value`.
bool read_preset(JsonReader& r, const Json& value, const std::string& path, Material& out) {
  std::string name;
  if (!r.string(value, path, name)) return false;
  const std::optional<Material> preset = material_preset(name);
  if (!preset) {
    return r.fail(path, "unknown preset \"" + name + "\" (known: " + preset_names() + ")");
  }
  out = *preset;
  return true;
}

/// The model's path: "models[0]" of "models[0].material".
std::string model_path(const std::string& material_path) {
  return material_path.substr(0, material_path.rfind('.'));
}

}  // namespace

std::string preset_names() {
  std::string names;
  for (const MaterialPreset& p : material_presets())
    names += (names.empty() ? "" : ", ") + std::string(p.name);
  return names;
}

bool read_material(JsonReader& r, const Json& value, const std::string& path, Material& out) {
  if (value.is_string()) return read_preset(r, value, path, out);
  if (!value.is_object()) {
    return r.fail(path, "expected a preset name (" + preset_names() +
                            ") or an object of material fields, got " + JsonReader::shown(value));
  }
  if (value.contains("friction")) {
    return r.fail(JsonReader::join(path, "friction"),
                  "friction belongs to the tool and the model, not the material: give it as " +
                      model_path(path) + ".friction");
  }
  if (!r.only_known(value, path,
                    {"preset", "density", "thickness", "youngs_modulus", "poisson_ratio",
                     "foundation_stiffness", "damping", "yield"})) {
    return false;
  }
  const Json* preset = r.member(value, path, "preset", false);
  if (preset != nullptr) {
    if (!read_preset(r, *preset, JsonReader::join(path, "preset"), out)) return false;
  } else {
    out = Material{};  // damping and yield keep their defaults; the rest is required below
  }
  const MaterialRange& range = kMaterialRange;
  const RangedField required[] = {
      {"density", &out.density, range.density, "kg/m^3"},
      {"thickness", &out.thickness, range.thickness, "mm"},
      {"youngs_modulus", &out.youngs_modulus, range.youngs_modulus, "MPa"},
      {"poisson_ratio", &out.poisson_ratio, range.poisson_ratio, ""},
      {"foundation_stiffness", &out.foundation_stiffness, range.foundation_stiffness, "N/mm^3"},
  };
  for (const RangedField& f : required) {
    const std::string field_path = JsonReader::join(path, f.key);
    const Json* v = r.member(value, path, f.key, false);
    if (v == nullptr) {
      if (preset != nullptr) continue;
      return r.fail(field_path,
                    "missing field (give every material field, or a \"preset\" to "
                    "start from: " +
                        preset_names() + ")");
    }
    if (!r.within(*v, field_path, *f.value, f.range, f.unit)) return false;
  }
  if (const Json* v = r.member(value, path, "damping", false)) {
    if (!r.within(*v, JsonReader::join(path, "damping"), out.damping, range.damping, "s")) {
      return false;
    }
  }
  if (const Json* v = r.member(value, path, "yield", false)) {
    if (!read_yield(r, *v, JsonReader::join(path, "yield"), range.yield, out.yield)) return false;
  }
  // Every field passed its own range: validate() agrees unless the two drift apart.
  const Status valid = validate(out);
  return valid.ok() || r.fail(path, valid.message);
}

bool read_version1_material(JsonReader& r, const Json& value, const std::string& path,
                            Material& out) {
  if (!r.only_known(value, path,
                    {"density", "stiffness", "damping", "anchor_stiffness", "yield", "friction"})) {
    return false;
  }
  Version1Material old;
  const Version1MaterialRange& range = kVersion1MaterialRange;
  const RangedField required[] = {{"density", &old.density, range.density, "kg/mm^2"},
                                  {"stiffness", &old.stiffness, range.stiffness, "N/mm"}};
  for (const RangedField& f : required) {
    const Json* v = r.member(value, path, f.key);
    if (v == nullptr || !r.within(*v, JsonReader::join(path, f.key), *f.value, f.range, f.unit)) {
      return false;
    }
  }
  const RangedField optional[] = {
      {"damping", &old.damping, range.damping, "s"},
      {"anchor_stiffness", &old.anchor_stiffness, range.anchor_stiffness, "N/mm"}};
  for (const RangedField& f : optional) {
    const Json* v = r.member(value, path, f.key, false);
    if (v != nullptr && !r.within(*v, JsonReader::join(path, f.key), *f.value, f.range, f.unit)) {
      return false;
    }
  }
  if (const Json* v = r.member(value, path, "yield", false)) {
    if (!read_yield(r, *v, JsonReader::join(path, "yield"), range.yield, old.yield)) return false;
  }
  const Result<Material> mapped = material_from_version1(old);
  if (!mapped.ok()) {
    return r.fail(path, mapped.status().message +
                            "; write the scene in version 2 to give this material "
                            "(argil materials lists the presets)");
  }
  out = mapped.value();
  return true;
}

}  // namespace argil::sculpt::internal
