// Named regression presses through the haptic tick (docs/deformation.md,
// Testing): a 1 mm sphere pressed into flat plates made of high-degree pieces
// joined C0 or C1, their 20 x 20 mm versions for locality, and every preset.
// Each press must stay finite, move no control point beyond the tool's reach,
// turn no normal further than the dent's own slope explains, and lose energy
// once the tool lets go.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "argil/core.hpp"
#include "support/sphere_press.hpp"
#include "support/test_plates.hpp"

namespace {

using argil::test::PlateShape;

struct NamedPlate {
  const char* name;
  int degree;
  int join;
};

/// The cases: two pieces of `degree` along v, joined with multiplicity `join`.
const std::vector<NamedPlate>& named_plates() {
  static const std::vector<NamedPlate> plates = {
      {"degree 10, C0 join", 10, 10},       {"degree 10, C1 join", 10, 9},
      {"degree 12, C0 join", 12, 12},       {"degree 9, C0 join", 9, 9},
      {"degree 8, C0 join", 8, 8},          {"degree 7, C0 join", 7, 7},
      {"degree 3, C0 join (control)", 3, 3}};
  return plates;
}

/// The 1 mm sphere pressed 0.3 mm at (0.37, 0.41) for 0.6 s, then released for 0.3 s.
argil::test::SpherePress named_press(const argil::Material& material, const Eigen::Vector2d& uv) {
  argil::test::SpherePress p;
  p.uv = uv;
  p.radius = 0.5;
  p.depth = 0.3;
  p.material = material;
  return p;
}

/// (D / k_a)^(1/4) [mm]: how far a bending plate on its foundation carries a
/// point load (the deflection decays like kei(r / L)).
double bending_length(const argil::Material& m) {
  const argil::ShellStiffness k = argil::shell_stiffness(m);
  return std::pow(k.bending / k.foundation, 0.25);
}

/// The checks every press must pass; `reach` is the bound on control-point moves.
void check_press(const argil::test::PressOutcome& r, const argil::test::SpherePress& p) {
  INFO(r.error);
  REQUIRE(r.error.empty());
  REQUIRE(r.finite);
  CHECK(r.contact_ticks > 0);
  CHECK(r.dent > 0.0);
  // The tool's reach: the device's sphere at its lowest reaches
  // device_penetration into the rest face (the press depth on a flat plate)
  // and the proxy never goes further than the device. A load that rises from
  // nothing carries the surface at most twice as far as it would hold it
  // (the overshoot of an oscillator's step response; damping and the
  // unilateral contact only lower it), and with depth <= radius that stays
  // within depth + radius; the control points of a flat plate's displacement
  // follow the surface's. Hence penetration + radius.
  const double reach = r.device_penetration + p.radius;
  CAPTURE(r.max_control_move, reach, r.dent, r.peak_force);
  CHECK(r.max_control_move <= reach);
  CAPTURE(r.normal_turn, r.turn_bound, r.displacement);
  CHECK(r.normal_turn <= r.turn_bound);
  CAPTURE(r.energy_rise, r.energy_at_release, r.energy_final);
  CHECK(r.energy_rise <= 1e-12);  // rounding of the energy sums only
  CHECK(r.energy_final <= r.energy_at_release);
}

}  // namespace

TEST_CASE("named plates: a 1 mm sphere pressed 0.3 mm into 1 x 1 mm plates of high-degree pieces",
          "[deformation][regression]") {
  for (const NamedPlate& plate : named_plates()) {
    const argil::BSplineSurface s = argil::test::flat_plate({.width = 1.0,
                                                             .height = 1.0,
                                                             .spans_u = 1,
                                                             .degree_v = plate.degree,
                                                             .pieces_v = 2,
                                                             .join_v = plate.join});
    REQUIRE(argil::validate(s).ok());
    for (const argil::MaterialPreset& preset : argil::material_presets()) {
      CAPTURE(plate.name, preset.name);
      const argil::test::SpherePress p = named_press(preset.material, {0.37, 0.41});
      check_press(argil::test::press_sphere(s, p), p);
    }
  }
}

// Known gap, kept visible: [!shouldfail] passes while the model misses this
// target and fails (asking for the tag to go) once it meets it. See
// docs/deformation.md, Limits.
TEST_CASE("named plates at 20 x 20 mm: the press stays local",
          "[deformation][regression][!shouldfail][slow]") {
  // The same knot structure in 1 mm pieces: degree 1 spans across, pieces of
  // the named degree along v.
  for (const NamedPlate& plate : named_plates()) {
    const argil::BSplineSurface s = argil::test::flat_plate({.width = 20.0,
                                                             .height = 20.0,
                                                             .spans_u = 20,
                                                             .degree_v = plate.degree,
                                                             .pieces_v = 20,
                                                             .join_v = plate.join});
    REQUIRE(argil::validate(s).ok());
    // The soft layers whose bending length leaves room for a far field on the plate.
    for (const char* name : {"clay", "wax"}) {
      const argil::Material m = *argil::material_preset(name);
      CAPTURE(plate.name, name);
      argil::test::SpherePress p = named_press(m, {0.37, 0.41});
      p.samples = 61;      // 0.33 mm apart: finer than the 0.46 mm footprint radius
      p.press_time = 0.3;  // the dent settles within tens of ms on these light layers
      p.release_time = 0.1;
      const argil::test::PressOutcome r = argil::test::press_sphere(s, p);
      check_press(r, p);
      // Far: four bending lengths (kei(4) is under 1% of kei(0)) plus the widest
      // basis support (2 mm: two degree-1 spans across, two C1 pieces along).
      const double length = bending_length(m);
      const double far = 4.0 * length + 2.0;
      const Eigen::Vector3d contact = argil::evaluate(s, 0.37, 0.41);
      double far_move = 0.0;
      int far_poles = 0;
      for (Eigen::Index i = 0; i < r.rest.rows(); ++i) {
        if ((r.rest.row(i).transpose() - contact).norm() <= far) continue;
        ++far_poles;
        far_move = std::max(far_move, (r.pressed.row(i) - r.rest.row(i)).norm());
      }
      CAPTURE(length, far, far_poles, far_move, r.dent);
      REQUIRE(far_poles > 0);
      CHECK(far_move < 0.05 * r.dent);
    }
  }
}
