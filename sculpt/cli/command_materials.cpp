// argil materials: the material presets a scene can name, with every value in
// its unit, and the range each material field is checked against.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "argil/core/base/number_text.hpp"
#include "argil/core/deform/material.hpp"
#include "commands.hpp"

namespace argil::cli {
namespace {

/// A material field as a scene spells it, its unit, its range and its value in a Material.
struct FieldColumn {
  const char* name;
  const char* unit;
  Interval range;
  double Material::*value;
};

const std::vector<FieldColumn>& field_columns() {
  const MaterialRange& r = kMaterialRange;
  static const std::vector<FieldColumn> columns = {
      {"density", "kg/m^3", r.density, &Material::density},
      {"thickness", "mm", r.thickness, &Material::thickness},
      {"youngs_modulus", "MPa", r.youngs_modulus, &Material::youngs_modulus},
      {"poisson_ratio", "", r.poisson_ratio, &Material::poisson_ratio},
      {"foundation_stiffness", "N/mm^3", r.foundation_stiffness, &Material::foundation_stiffness},
      {"damping", "s", r.damping, &Material::damping},
      {"yield", "mm", r.yield, &Material::yield},
  };
  return columns;
}

/// A value as a scene would give it: an infinite yield is "none" (purely elastic).
std::string scene_value(double x) { return std::isinf(x) ? "none" : number_text(x); }

/// `rows` with every column padded to its widest cell, two spaces apart.
std::string table(const std::vector<std::vector<std::string>>& rows) {
  std::vector<std::size_t> width;
  for (const auto& row : rows) {
    width.resize(std::max(width.size(), row.size()), 0);
    for (std::size_t c = 0; c < row.size(); ++c) width[c] = std::max(width[c], row[c].size());
  }
  std::string out;
  for (const auto& row : rows) {
    std::string line;
    for (std::size_t c = 0; c < row.size(); ++c) {
      line += row[c];
      if (c + 1 < row.size()) line += std::string(width[c] + 2 - row[c].size(), ' ');
    }
    out += line + "\n";
  }
  return out;
}

std::string presets_text() {
  std::vector<std::vector<std::string>> values{{"preset"}, {""}};
  for (const FieldColumn& f : field_columns()) {
    values[0].emplace_back(f.name);
    values[1].emplace_back(*f.unit == '\0' ? "-" : f.unit);
  }
  std::vector<std::vector<std::string>> descriptions;
  for (const MaterialPreset& p : material_presets()) {
    std::vector<std::string> row{std::string(p.name)};
    for (const FieldColumn& f : field_columns()) row.push_back(scene_value(p.material.*f.value));
    values.push_back(std::move(row));
    descriptions.push_back({std::string(p.name), std::string(p.description)});
  }
  std::vector<std::vector<std::string>> ranges;
  for (const FieldColumn& f : field_columns()) {
    std::string range = interval_text(f.range, f.unit);
    if (std::isinf(f.range.high)) range += ", or \"none\" (purely elastic)";
    ranges.push_back({std::string("  ") + f.name, range});
  }
  return table(values) + "\n" + table(descriptions) +
         "\nranges (a scene's material fields are checked against them):\n" + table(ranges);
}

}  // namespace

const CommandDeclaration& materials_command() {
  static const CommandDeclaration spec{
      .name = "materials",
      .operands = {},
      .summary = "list the material presets a scene can name, with their values",
      .description =
          "A scene (version 2) names a preset as \"material\": \"clay\", or starts from one\n"
          "and overrides fields: \"material\": {\"preset\": \"clay\", \"thickness\": 3}.",
      .options = {},
  };
  return spec;
}

int run_materials(const std::vector<std::string>& args) {
  const ParseResult parsed = parse_arguments(materials_command(), args);
  if (!parsed.arguments) return parsed.exit_status;
  std::fputs(presets_text().c_str(), stdout);
  return kExitOk;
}

}  // namespace argil::cli
