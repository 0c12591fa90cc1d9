// Scene materials, version 2: presets by name, a preset with fields overriding
// it, every field given explicitly, and errors naming the file, the model and
// the field with the valid preset names or the field's range (kMaterialRange,
// the range validate() uses).
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "argil/core/base/number_text.hpp"
#include "argil/sculpt/scene/scene.hpp"

namespace argil::sculpt {
namespace {

/// A material field as a scene spells it, its unit and its range.
struct Field {
  const char* key;
  double Material::*member;
  const char* unit;
  Interval range;
};

const std::vector<Field>& fields() {
  const MaterialRange& r = kMaterialRange;
  static const std::vector<Field> all = {
      {"density", &Material::density, "kg/m^3", r.density},
      {"thickness", &Material::thickness, "mm", r.thickness},
      {"youngs_modulus", &Material::youngs_modulus, "MPa", r.youngs_modulus},
      {"poisson_ratio", &Material::poisson_ratio, "", r.poisson_ratio},
      {"foundation_stiffness", &Material::foundation_stiffness, "N/mm^3", r.foundation_stiffness},
      {"damping", &Material::damping, "s", r.damping},
      {"yield", &Material::yield, "mm", r.yield},
  };
  return all;
}

/// A scene whose second model (models[1], "hood") has `material` as its material.
std::string scene_with(const std::string& material) {
  return R"({"format": "argil.scene", "version": 2, "tolerance": 0.05,
    "models": [{"name": "frame", "file": "frame.json", "kind": "rigid"},
               {"name": "hood", "file": "hood.json", "material": )" +
         material + R"(}],
    "tools": [{"name": "p", "type": "point"}]})";
}

Result<Material> material_of(const std::string& material) {
  const Result<Scene> r = parse_scene(scene_with(material), "s.json", ".");
  if (!r.ok()) return r.status();
  return r.value().models[1].material;
}

/// Every field of `a` equals the same field of `b` except `except` (nullptr: none).
void check_same_except(const Material& a, const Material& b, double Material::*except) {
  for (const Field& f : fields()) {
    if (f.member == except) continue;
    INFO(f.key);
    CHECK(a.*f.member == b.*f.member);
  }
}

/// The JSON text of a value a scene gives a field: infinity is "none".
std::string json_value(double x) { return std::isinf(x) ? "\"none\"" : number_text(x); }

/// The explicit material object of `m`, leaving out the field `skip` (or none).
std::string explicit_object(const Material& m, const char* skip = "") {
  std::string text;
  for (const Field& f : fields()) {
    if (std::string(f.key) == skip) continue;
    text +=
        (text.empty() ? "{" : ", ") + std::string("\"") + f.key + "\": " + json_value(m.*f.member);
  }
  return text + "}";
}

void check_error(const std::string& material, const std::string& expected) {
  const Result<Material> r = material_of(material);
  INFO(material);
  REQUIRE_FALSE(r.ok());
  INFO(r.status().message);
  CHECK(r.status().message.rfind("s.json: ", 0) == 0);
  CHECK(r.status().message.find(expected) != std::string::npos);
}

TEST_CASE("every preset reads by name with exactly its values", "[scene][material]") {
  REQUIRE_FALSE(material_presets().empty());
  for (const MaterialPreset& p : material_presets()) {
    INFO(p.name);
    const Result<Material> named = material_of("\"" + std::string(p.name) + "\"");
    INFO(named.status().message);
    REQUIRE(named.ok());
    check_same_except(named.value(), p.material, nullptr);
    const Result<Material> object = material_of("{\"preset\": \"" + std::string(p.name) + "\"}");
    REQUIRE(object.ok());
    check_same_except(object.value(), p.material, nullptr);
    CHECK(validate(named.value()).ok());
  }
}

TEST_CASE("a field given beside a preset overrides that field only", "[scene][material]") {
  for (const MaterialPreset& p : material_presets()) {
    for (const Field& f : fields()) {
      // Inside every field's range, and different from the preset's value.
      const double value = p.material.*f.member == 0.3 ? 0.2 : 0.3;
      INFO(p.name << " " << f.key << " " << value);
      const Result<Material> r = material_of("{\"preset\": \"" + std::string(p.name) + "\", \"" +
                                             f.key + "\": " + number_text(value) + "}");
      INFO(r.status().message);
      REQUIRE(r.ok());
      CHECK(r.value().*f.member == value);
      check_same_except(r.value(), p.material, f.member);
    }
  }
  const Result<Material> elastic = material_of(R"({"preset": "clay", "yield": "none"})");
  REQUIRE(elastic.ok());
  CHECK(std::isinf(elastic.value().yield));
  CHECK(std::isfinite(material_preset("clay")->yield));
}

TEST_CASE("a material given field by field reads every field", "[scene][material]") {
  const Material m{.density = 2500,
                   .thickness = 0.8,
                   .youngs_modulus = 1200,
                   .poisson_ratio = 0.31,
                   .foundation_stiffness = 4.5,
                   .damping = 0.002,
                   .yield = 0.05};
  const Result<Material> r = material_of(explicit_object(m));
  INFO(r.status().message);
  REQUIRE(r.ok());
  check_same_except(r.value(), m, nullptr);
}

TEST_CASE("an unknown preset names the model field and the known presets",
          "[scene][material][bad-input]") {
  for (const std::string& material :
       {std::string("\"steel\""), std::string(R"({"preset": "steel", "thickness": 2})")}) {
    const Result<Material> r = material_of(material);
    REQUIRE_FALSE(r.ok());
    const std::string& message = r.status().message;
    INFO(message);
    const std::string path =
        material[0] == '"' ? "models[1].material: " : "models[1].material.preset: ";
    CHECK(message.rfind("s.json: " + path + "unknown preset \"steel\" (known: ", 0) == 0);
    for (const MaterialPreset& p : material_presets()) {
      CHECK(message.find(std::string(p.name)) != std::string::npos);
    }
  }
  check_error("\"Clay\"", "models[1].material: unknown preset \"Clay\"");  // names are exact
}

TEST_CASE("each material field out of its range names the field, the range and the value",
          "[scene][material][bad-input]") {
  const Material clay = *material_preset("clay");
  for (const Field& f : fields()) {
    std::vector<double> bad = {f.range.low == 0.0 ? -1.0 : f.range.low / 10.0,
                               -std::numeric_limits<double>::min()};
    if (std::isfinite(f.range.high)) {
      const bool open_high =
          f.range.ends == IntervalEnds::open || f.range.ends == IntervalEnds::open_high;
      bad.push_back(open_high ? f.range.high : f.range.high * 10.0);
    }
    for (const double value : bad) {
      if (f.range.contains(value)) continue;  // -tiny is inside no range starting at 0 or above
      const std::string expected = "models[1].material." + std::string(f.key) + ": " +
                                   out_of_interval_text(value, f.range, f.unit);
      check_error(
          "{\"preset\": \"clay\", \"" + std::string(f.key) + "\": " + number_text(value) + "}",
          expected);
      Material m = clay;
      m.*f.member = value;
      check_error(explicit_object(m), expected);
    }
    check_error("{\"preset\": \"clay\", \"" + std::string(f.key) + "\": NaN}",
                "models[1].material." + std::string(f.key) + ": NaN is not allowed");
  }
  // The same message in words, for one field: the open end of Poisson's ratio.
  check_error(R"({"preset": "clay", "poisson_ratio": 0.5})",
              "models[1].material.poisson_ratio: must be in [0, 0.5), got 0.5");
}

TEST_CASE("the scene reader accepts exactly the material values validate() accepts",
          "[scene][material]") {
  const Material clay = *material_preset("clay");
  for (const Field& f : fields()) {
    for (const double end : {f.range.low, f.range.high}) {
      Material m = clay;
      m.*f.member = end;
      INFO(f.key << " = " << end);
      const Result<Material> r = material_of(explicit_object(m));
      CHECK(r.ok() == validate(m).ok());
      CHECK(r.ok() == f.range.contains(end));
    }
  }
}

TEST_CASE("material errors of the wrong type, missing or unknown fields name the field",
          "[scene][material][bad-input]") {
  check_error("3",
              "models[1].material: expected a preset name (clay, wax, foam, sheet_steel, "
              "aluminium, abs) or an object of material fields, got 3");
  check_error("[\"clay\"]", "models[1].material: expected a preset name");
  check_error("null", "models[1].material: expected a preset name");
  check_error(R"({"preset": 3})", "models[1].material.preset: expected a string, got 3");
  check_error(R"({"preset": "clay", "thickness": "3"})",
              "models[1].material.thickness: expected a number, got \"3\"");
  check_error(R"({"preset": "clay", "yield": true})",
              "models[1].material.yield: expected a number, got true");
  check_error(R"({"preset": "clay", "density": null})",
              "models[1].material.density: null where a number belongs");
  check_error(R"({"preset": "clay", "stiffness": 3})",
              "models[1].material.stiffness: unknown field (known: preset, density, thickness, "
              "youngs_modulus, poisson_ratio, foundation_stiffness, damping, yield)");
  check_error(R"({"preset": "clay", "friction": 0.4})",
              "models[1].material.friction: friction belongs to the tool and the model, not the "
              "material: give it as models[1].friction");
  // Without a preset every field but damping and yield is required.
  const Material clay = *material_preset("clay");
  for (const char* key :
       {"density", "thickness", "youngs_modulus", "poisson_ratio", "foundation_stiffness"}) {
    check_error(explicit_object(clay, key), "models[1].material." + std::string(key) +
                                                ": missing field (give every material field, "
                                                "or a \"preset\" to start from");
  }
  const Result<Material> no_damping = material_of(explicit_object(clay, "damping"));
  REQUIRE(no_damping.ok());
  CHECK(no_damping.value().damping == Material{}.damping);
  const Result<Material> no_yield = material_of(explicit_object(clay, "yield"));
  REQUIRE(no_yield.ok());
  CHECK(std::isinf(no_yield.value().yield));  // purely elastic
  const Result<Scene> no_material = parse_scene(
      R"({"format": "argil.scene", "version": 2, "tolerance": 1,
          "models": [{"name": "m", "file": "m.json"}], "tools": [{"name": "p", "type": "point"}]})",
      "s.json", ".");
  REQUIRE_FALSE(no_material.ok());
  CHECK(no_material.status().message ==
        "s.json: models[0].material: missing field (a deformable model needs a material)");
}

TEST_CASE("friction is the model's in version 2, for deformable and rigid models alike",
          "[scene][material]") {
  const Result<Scene> r = parse_scene(
      R"({"format": "argil.scene", "version": 2, "tolerance": 1,
          "models": [{"name": "soft", "file": "m.json", "material": "foam", "friction": 0.6},
                     {"name": "hard", "file": "m.json", "kind": "rigid", "friction": 0.1},
                     {"name": "plain", "file": "m.json", "material": "wax"}],
          "tools": [{"name": "p", "type": "point"}]})",
      "s.json", ".");
  INFO(r.status().message);
  REQUIRE(r.ok());
  CHECK(r.value().models[0].friction == 0.6);
  CHECK(r.value().models[1].friction == 0.1);
  CHECK(r.value().models[2].friction == ModelOptions{}.friction);
  CHECK(r.value().warnings.empty());
}

}  // namespace
}  // namespace argil::sculpt
