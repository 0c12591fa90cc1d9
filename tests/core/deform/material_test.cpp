// Materials (docs/deformation.md): validate() names every field outside its
// documented range with the value and the range in the field's unit, NaN
// included; every preset is valid and found by name; a material too stiff
// for its mass on a face is refused naming the dimensionless ratio.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "argil/core.hpp"
#include "support/random_surface.hpp"

namespace {

struct Field {
  const char* name;
  double argil::Material::*member;
  argil::Interval range;
  const char* unit;
};

/// Every Material field with its documented range and unit.
std::vector<Field> fields() {
  const argil::MaterialRange& r = argil::kMaterialRange;
  return {{"density", &argil::Material::density, r.density, "kg/m^3"},
          {"thickness", &argil::Material::thickness, r.thickness, "mm"},
          {"youngs_modulus", &argil::Material::youngs_modulus, r.youngs_modulus, "MPa"},
          {"poisson_ratio", &argil::Material::poisson_ratio, r.poisson_ratio, ""},
          {"foundation_stiffness", &argil::Material::foundation_stiffness, r.foundation_stiffness,
           "N/mm^3"},
          {"damping", &argil::Material::damping, r.damping, "s"},
          {"yield", &argil::Material::yield, r.yield, "mm"}};
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace

TEST_CASE("validate(Material) names every field out of range, its value and range in its unit",
          "[deformation][material]") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const Field& f : fields()) {
    // Just outside each finite end, far outside, and NaN.
    std::vector<double> bad{nan, -1.0};
    if (f.range.low != 0.0) bad.push_back(f.range.low * 0.5);
    if (std::isfinite(f.range.high)) bad.push_back(f.range.high * 2.0);
    if (f.range.ends == argil::IntervalEnds::open_high) bad.push_back(f.range.high);
    for (const double value : bad) {
      argil::Material m;
      m.*f.member = value;
      const argil::Status s = argil::validate(m);
      CAPTURE(f.name, value, s.message);
      REQUIRE_FALSE(s.ok());
      CHECK(s.code == argil::StatusCode::invalid_argument);
      CHECK(contains(s.message, std::string("material.") + f.name + " "));
      CHECK(contains(s.message, "got " + argil::number_text(value)));
      CHECK(contains(s.message, argil::number_text(f.range.low)));
      if (std::isfinite(f.range.high)) CHECK(contains(s.message, argil::number_text(f.range.high)));
      if (*f.unit != '\0') CHECK(contains(s.message, std::string(" ") + f.unit));
    }
    // Both closed ends are accepted.
    for (const double value : {f.range.low, f.range.high}) {
      if (value == f.range.high && f.range.ends == argil::IntervalEnds::open_high) continue;
      argil::Material m;
      m.*f.member = value;
      CAPTURE(f.name, value);
      CHECK(argil::validate(m).ok());
    }
  }
  // The first bad field in declaration order is the one named.
  argil::Material m;
  m.damping = -1.0;
  m.density = nan;
  CHECK(contains(argil::validate(m).message, "material.density "));
}

TEST_CASE("every preset is valid, distinct and found by name", "[deformation][material]") {
  const std::vector<argil::MaterialPreset>& presets = argil::material_presets();
  REQUIRE(presets.size() >= 6);
  for (std::size_t i = 0; i < presets.size(); ++i) {
    CAPTURE(presets[i].name);
    CHECK(argil::validate(presets[i].material).ok());
    CHECK_FALSE(presets[i].description.empty());
    const auto found = argil::material_preset(presets[i].name);
    REQUIRE(found.has_value());
    CHECK(found->youngs_modulus == presets[i].material.youngs_modulus);
    for (std::size_t j = 0; j < i; ++j) CHECK(presets[j].name != presets[i].name);
  }
  CHECK_FALSE(argil::material_preset("putty").has_value());
}

TEST_CASE("shell stiffnesses follow the plate formulas", "[deformation][material]") {
  const argil::Material m{.density = 2000,
                          .thickness = 2,
                          .youngs_modulus = 300,
                          .poisson_ratio = 0.25,
                          .foundation_stiffness = 4};
  const argil::ShellStiffness k = argil::shell_stiffness(m);
  CHECK(k.membrane == Approx(300.0 * 2.0 / (1.0 - 0.0625)).epsilon(1e-15));
  CHECK(k.bending == Approx(300.0 * 8.0 / (12.0 * (1.0 - 0.0625))).epsilon(1e-15));
  CHECK(k.foundation == 4.0);
  CHECK(k.mass_per_area == Approx(2000.0 * 1e-9 * 2.0).epsilon(1e-15));  // kg/m^3 -> kg/mm^2
}

TEST_CASE("a material too stiff for its mass is accepted with its elastic terms capped",
          "[deformation][material]") {
  const argil::BSplineSurface s = argil::test::asymmetric_surface();
  // Valid field by field: the lightest, thinnest layer with the stiffest modulus.
  const argil::Material m{.density = 1e-3,
                          .thickness = 1e-6,
                          .youngs_modulus = 1e7,
                          .poisson_ratio = 0.3,
                          .foundation_stiffness = 0.0};
  REQUIRE(argil::validate(m).ok());
  argil::OperatorCache cache;
  auto created = argil::DeformableBody::create(s, m, {}, cache);
  REQUIRE(created.ok());
  argil::DeformableBody body = std::move(created).value();
  CHECK(body.elastic_scale() < 1.0);
  CHECK(body.elastic_scale() > 0.0);
  // Every control point now reaches the documented ratio at the haptic step.
  const double h2 = argil::kHapticStep * argil::kHapticStep;
  for (Eigen::Index i = 0; i < body.masses().size(); ++i) {
    const double inertia = argil::kMassToNewtonSecond2PerMm * body.masses()[i];
    CHECK(inertia >= (1.0 - 1e-9) * argil::kMaterialRange.min_inertia_ratio * h2 *
                         body.stiffness().diagonal(i));
  }
  // And it steps cleanly: pushed, then released, its energy never grows by
  // more than the rounding the ratio allows (as in the stability sweep). The
  // body floats (no foundation): its drift costs no energy and is taken out
  // before the quadratic form, whose rounding would otherwise grow with it.
  const auto energy = [&] {
    argil::ControlNet u = body.control_points() - body.rest_control_points();
    u.rowwise() -= u.colwise().mean();
    return body.kinetic_energy() + 0.5 * body.stiffness().quadratic_form(u);
  };
  argil::ControlNet push = argil::ControlNet::Zero(body.masses().size(), 3);
  push(3, 2) = 1e-9;
  REQUIRE(body.step(argil::kHapticStep, push).ok());
  const double rounding =
      64.0 * std::numeric_limits<double>::epsilon() / argil::kMaterialRange.min_inertia_ratio;
  double last = energy();
  for (int t = 0; t < 100; ++t) {
    REQUIRE(body.step(argil::kHapticStep).ok());
    const double now = energy();
    CAPTURE(now / last - 1.0, rounding);
    CHECK(now <= last * (1.0 + rounding));
    last = now;
  }
  // Clay needs no cap on this face.
  const auto clay_like =
      argil::DeformableBody::create(s, *argil::material_preset("clay"), {}, cache);
  REQUIRE(clay_like.ok());
  CHECK(clay_like.value().elastic_scale() == 1.0);
}
