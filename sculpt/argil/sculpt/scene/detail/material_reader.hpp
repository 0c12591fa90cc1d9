#pragma once
// Private to argil::sculpt: a scene's "material" in either schema version
// (docs/formats.md), every field checked against the range its validator
// uses and every error naming the field's path.

#include <string>

#include "argil/core/deform/material.hpp"
#include "argil/sculpt/detail/json_reader.hpp"

namespace argil::sculpt::internal {

/// Version 2: a preset name ("clay"), or an object with an optional "preset"
/// and any Material field overriding it; without a preset every field but
/// damping and yield is required. Friction is not a material field here.
bool read_material(JsonReader& reader, const Json& value, const std::string& path, Material& out);

/// Version 1: areal density, spring stiffness, damping, anchor_stiffness and
/// yield, mapped by material_from_version1. A "friction" member is allowed
/// and left to the caller.
bool read_version1_material(JsonReader& reader, const Json& value, const std::string& path,
                            Material& out);

/// "clay, wax, ...": the preset names, for messages.
std::string preset_names();

}  // namespace argil::sculpt::internal
