// Version-1 scenes: their mass-spring materials map to physical units as
// docs/formats.md states (mass per area and membrane stiffness kept, anchors
// per 1 mm^2), the reader warns that it mapped them, and numbers without a
// physical counterpart are errors naming the field.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <string>

#include "argil/core/base/number_text.hpp"
#include "argil/sculpt/scene/scene.hpp"
#include "argil/sculpt/scene/version1_material.hpp"

namespace argil::sculpt {
namespace {

bool close(double a, double b, double relative) {
  return std::abs(a - b) <= relative * std::max(std::abs(a), std::abs(b));
}

/// The documented invariants of a mapped material, checked through the
/// shell stiffness the physics derives from it.
void check_mapping(const Version1Material& old, const Material& m) {
  CHECK(validate(m).ok());
  const ShellStiffness shell = shell_stiffness(m);
  CHECK(close(shell.mass_per_area, old.density, 1e-14));  // kg/mm^2
  CHECK(close(shell.membrane, old.stiffness, 1e-14));     // N/mm
  CHECK(m.poisson_ratio == 0.0);
  CHECK(shell.foundation == old.anchor_stiffness / 1.0);  // per 1 mm^2 of surface
  CHECK(m.damping == old.damping);
  CHECK(m.yield == old.yield);
}

TEST_CASE("a version-1 material keeps its mass per area and membrane stiffness at 1 mm",
          "[scene][version1]") {
  // The examples' version-1 numbers, and a stiff and a heavy one.
  const Version1Material olds[] = {
      {.density = 1e-5, .stiffness = 0.5, .damping = 0.001, .anchor_stiffness = 0.5, .yield = 0.3},
      {.density = 2e-6, .stiffness = 3, .damping = 0.02, .anchor_stiffness = 0, .yield = 0.1},
      {.density = 7.85e-6, .stiffness = 2e5, .damping = 0, .anchor_stiffness = 1e3},
      {.density = 1e-4, .stiffness = 0, .damping = 1, .anchor_stiffness = 1e9, .yield = 1e-9},
  };
  for (const Version1Material& old : olds) {
    INFO("density " << old.density << " stiffness " << old.stiffness);
    const Result<Material> m = material_from_version1(old);
    INFO(m.status().message);
    REQUIRE(m.ok());
    CHECK(m.value().thickness == 1.0);
    check_mapping(old, m.value());
  }
  // 1e-5 kg/mm^2 over 1 mm is 1e-5 kg/mm^3 = 10000 kg/m^3; 0.5 N/mm over 1 mm is 0.5 MPa.
  const Material groove = material_from_version1(olds[0]).value();
  CHECK(close(groove.density, 10000.0, 1e-15));
  CHECK(groove.youngs_modulus == 0.5);
  CHECK(groove.foundation_stiffness == 0.5);
}

TEST_CASE("a version-1 material moves off 1 mm only as far as the ranges require",
          "[scene][version1]") {
  // 0.01 kg/mm^2 over 1 mm would be 1e7 kg/m^3, above 1e5: 100 mm brings it to 1e5.
  const Version1Material heavy{.density = 0.01, .stiffness = 1};
  const Result<Material> h = material_from_version1(heavy);
  REQUIRE(h.ok());
  CHECK(close(h.value().thickness, 100.0, 1e-14));
  CHECK(close(h.value().density, 1e5, 1e-14));
  check_mapping(heavy, h.value());
  // 1e9 N/mm over 1 mm would be 1e9 MPa, above 1e7: 100 mm brings it to 1e7.
  const Version1Material stiff{.density = 1e-5, .stiffness = 1e9};
  const Result<Material> s = material_from_version1(stiff);
  REQUIRE(s.ok());
  CHECK(close(s.value().thickness, 100.0, 1e-14));
  CHECK(close(s.value().youngs_modulus, 1e7, 1e-14));
  check_mapping(stiff, s.value());
  // 1e-15 kg/mm^2 over 1 mm would be 1e-6 kg/m^3, below 1e-3: 1e-3 mm brings it to 1e-3.
  const Version1Material light{.density = 1e-15, .stiffness = 1e-3};
  const Result<Material> l = material_from_version1(light);
  REQUIRE(l.ok());
  CHECK(close(l.value().thickness, 1e-3, 1e-14));
  check_mapping(light, l.value());
}

TEST_CASE("version-1 numbers map exactly when some thickness allows it (dense sweep)",
          "[scene][version1]") {
  // Brute force oracle: a mapping exists iff some thickness on a dense
  // logarithmic grid (plus 1 mm) keeps density and youngs_modulus in range.
  const MaterialRange& r = kMaterialRange;
  const auto fits = [&](const Version1Material& old, double h) {
    return r.density.contains(old.density / (h * kKgPerM3ToKgPerMm3)) &&
           r.youngs_modulus.contains(old.stiffness / h) && r.thickness.contains(h);
  };
  std::mt19937 rng(2024);
  std::uniform_real_distribution<double> exponent(0.0, 1.0);
  const auto log_uniform = [&](double low, double high) {
    return low * std::pow(high / low, exponent(rng));
  };
  int mapped = 0, refused = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const Version1Material old{.density = log_uniform(1e-15, 1e3),
                               .stiffness = log_uniform(1e-3, 1e9),
                               .anchor_stiffness = log_uniform(1e-3, 1e9)};
    bool any = false;
    for (int k = 0; k <= 2000 && !any; ++k) any = fits(old, std::pow(10.0, -6.0 + 10.0 * k / 2000));
    const Result<Material> m = material_from_version1(old);
    INFO("density " << number_text(old.density) << " stiffness " << number_text(old.stiffness)
                    << ": " << m.status().message);
    // The grid can miss a sliver of thicknesses; a mapping the grid misses
    // must then sit at the edge of what fits.
    if (any) REQUIRE(m.ok());
    if (!m.ok()) {
      ++refused;
      CHECK(m.status().code == StatusCode::invalid_argument);
      CHECK(m.status().message.find("has no physical counterpart") != std::string::npos);
      continue;
    }
    ++mapped;
    check_mapping(old, m.value());
    // 1 mm when it fits, else the thickness closest to it that does.
    if (fits(old, 1.0)) {
      CHECK(m.value().thickness == 1.0);
    } else {
      const double h = m.value().thickness;
      const bool nearer_fits = fits(old, h < 1.0 ? h * (1 + 1e-9) : h * (1 - 1e-9));
      CHECK_FALSE(nearer_fits);
    }
  }
  CHECK(mapped > 100);  // both outcomes were exercised
  CHECK(refused > 10);
}

TEST_CASE("version-1 numbers out of their range or without a counterpart name the field",
          "[scene][version1][bad-input]") {
  const std::pair<Version1Material, std::string> cases[] = {
      {{.density = 1e-5, .stiffness = -3}, "stiffness must be in [0, 1e+09] N/mm, got -3 N/mm"},
      {{.density = 0, .stiffness = 1}, "density must be in [1e-15, 1000] kg/mm^2, got 0 kg/mm^2"},
      {{.density = 1e-5, .stiffness = 1, .damping = 2}, "damping must be in [0, 1] s, got 2 s"},
      {{.density = 1e-5, .stiffness = 1, .anchor_stiffness = -1},
       "anchor_stiffness must be in [0, 1e+09] N/mm, got -1 N/mm"},
      {{.density = 1e-5, .stiffness = 1, .yield = 0}, "yield must be in [1e-09, inf] mm, got 0 mm"},
      // Above 1 kg/mm^2 (1e5 kg/m^3 over 1e4 mm) no thickness holds the mass.
      {{.density = 100, .stiffness = 200},
       "density 100 kg/mm^2 has no physical counterpart: density x thickness spans [1e-18, 1] "
       "kg/mm^2"},
      // 1e9 N/mm needs 100 mm for E <= 1e7 MPa, where 1e-12 kg/mm^2 is 1e-5 kg/m^3.
      {{.density = 1e-12, .stiffness = 1e9},
       "stiffness 1e+09 N/mm with density 1e-12 kg/mm^2 has no physical counterpart: "
       "youngs_modulus = stiffness / thickness needs a thickness of at least 100 mm, where the "
       "density falls below 0.001 kg/m^3"},
  };
  for (const auto& [old, expected] : cases) {
    const Result<Material> m = material_from_version1(old);
    INFO(expected);
    REQUIRE_FALSE(m.ok());
    CHECK(m.status().code == StatusCode::invalid_argument);
    CHECK(m.status().message == expected);
  }
}

const char* kVersion1Scene = R"({
  "format": "argil.scene", "version": 1, "tolerance": 0.05,
  "models": [
    {"name": "frame", "file": "frame.json", "kind": "rigid", "friction": 0.15},
    {"name": "plate", "file": "plate.json",
     "material": {"density": 1e-5, "stiffness": 0.5, "damping": 0.002, "anchor_stiffness": 0.25,
                  "yield": 0.2, "friction": 0.4}}],
  "tools": [{"name": "pin", "type": "point"}]})";

/// The version-1 scene with one substitution (`from` must occur once).
std::string edited(const std::string& from, const std::string& to) {
  std::string s = kVersion1Scene;
  const std::size_t at = s.find(from);
  REQUIRE(at != std::string::npos);
  REQUIRE(s.find(from, at + 1) == std::string::npos);
  return s.replace(at, from.size(), to);
}

TEST_CASE("a version-1 scene reads with its material mapped and a warning saying so",
          "[scene][version1]") {
  const Result<Scene> r = parse_scene(kVersion1Scene, "old.json", ".");
  INFO(r.status().message);
  REQUIRE(r.ok());
  const Scene& s = r.value();
  CHECK(s.version == 1);
  const Version1Material old{
      .density = 1e-5, .stiffness = 0.5, .damping = 0.002, .anchor_stiffness = 0.25, .yield = 0.2};
  check_mapping(old, s.models[1].material);
  CHECK(s.models[1].material.thickness == 1.0);
  CHECK(s.models[1].friction == 0.4);  // version 1: material.friction
  CHECK(s.models[0].friction == 0.15);
  REQUIRE(s.warnings.size() == 1);  // one per deformable model
  const std::string& w = s.warnings[0];
  INFO(w);
  CHECK(w.rfind("old.json: models[1].material: version-1 material mapped to physical units: ", 0) ==
        0);
  CHECK(w.find("density 10000 kg/m^3, thickness 1 mm, youngs_modulus 0.5 MPa, poisson_ratio 0, "
               "foundation_stiffness 0.25 N/mm^3") != std::string::npos);
  CHECK(w.find("feels different") != std::string::npos);
  // A yield of "none" is elastic in version 1 too.
  const Result<Scene> elastic =
      parse_scene(edited("\"yield\": 0.2", "\"yield\": \"none\""), "old.json", ".");
  REQUIRE(elastic.ok());
  CHECK(std::isinf(elastic.value().models[1].material.yield));
}

TEST_CASE("a committed version-1 scene file still reads", "[scene][version1]") {
  const std::filesystem::path path =
      std::filesystem::path(ARGIL_SOURCE_DIR) / "tests/data/sculpt/version1.json";
  const Result<Scene> r = read_scene(path);
  INFO(r.status().message);
  REQUIRE(r.ok());
  CHECK(r.value().version == 1);
  REQUIRE(r.value().warnings.size() == 1);
  CHECK(r.value().warnings[0].rfind(path.string() + ": models[0].material: version-1", 0) == 0);
}

TEST_CASE("version-1 scene errors name the file, the model and the field",
          "[scene][version1][bad-input]") {
  const std::pair<std::string, std::string> cases[] = {
      {edited("\"stiffness\": 0.5", "\"stiffness\": -3"),
       "models[1].material.stiffness: must be in [0, 1e+09] N/mm, got -3 N/mm"},
      {edited("\"density\": 1e-5", "\"density\": 0"),
       "models[1].material.density: must be in [1e-15, 1000] kg/mm^2, got 0 kg/mm^2"},
      {edited("\"density\": 1e-5, ", ""), "models[1].material.density: missing field"},
      {edited("\"density\": 1e-5", "\"density\": 100"),
       "models[1].material: density 100 kg/mm^2 has no physical counterpart"},
      {edited("\"anchor_stiffness\": 0.25", "\"anchor_stiffness\": \"high\""),
       "models[1].material.anchor_stiffness: expected a number"},
      {edited("\"damping\": 0.002", "\"thickness\": 2"),
       "models[1].material.thickness: unknown field (known: density, stiffness, damping, "
       "anchor_stiffness, yield, friction)"},
      {edited("\"friction\": 0.4", "\"friction\": 11"),
       "models[1].material.friction: must be in [0, 10], got 11"},
      {edited("\"name\": \"plate\",", "\"name\": \"plate\", \"friction\": 0.4,"),
       "models[1].friction: a version-1 scene gives a deformable model's friction as "
       "material.friction"},
      {edited("\"material\": {", "\"material\": \"clay\", \"old\": {"),
       "models[1].old: unknown field"},
  };
  for (const auto& [text, expected] : cases) {
    const Result<Scene> r = parse_scene(text, "old.json", ".");
    INFO(expected);
    REQUIRE_FALSE(r.ok());
    INFO(r.status().message);
    CHECK(r.status().message.rfind("old.json: ", 0) == 0);
    CHECK(r.status().message.find(expected) != std::string::npos);
  }
  // Presets are version 2: a version-1 material must be the object of old fields.
  const Result<Scene> preset =
      parse_scene(R"({"format": "argil.scene", "version": 1, "tolerance": 1,
                      "models": [{"name": "m", "file": "m.json", "material": "clay"}],
                      "tools": [{"name": "p", "type": "point"}]})",
                  "old.json", ".");
  REQUIRE_FALSE(preset.ok());
  CHECK(preset.status().message.find("old.json: models[0].material: expected an object") !=
        std::string::npos);
}

}  // namespace
}  // namespace argil::sculpt
