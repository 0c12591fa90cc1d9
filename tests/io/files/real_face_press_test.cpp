// Every face of every real CAD file argil reads (tests/data), pressed by a
// sphere sized to the face (docs/deformation.md, Testing): no NaN, no control
// point beyond the tool's reach, no normal turned further than the dent's
// slope explains, no energy gained after the tool lets go. Every face runs
// with clay; the other presets run on a deterministic sample (every fifth
// face, the preset rotating) to keep the suite within minutes on two cores;
// the sanitizer build presses every fourth face.
// Every preset must be accepted on every face of bearing.iges (0.16 mm
// across) and on a 1 m panel.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "argil/io.hpp"
#include "support/sphere_press.hpp"
#include "support/test_plates.hpp"
#include "support/uniform_refinement.hpp"
#include "test_files.hpp"

namespace {

using argil::BSplineSurface;

/// The press for a face: a sphere a tenth of the face's size pressed 0.3 of
/// its radius at the middle of the parameter domain, 0.1 s, then 0.05 s released.
argil::test::SpherePress press_for(const BSplineSurface& face, const argil::Material& m) {
  const double size = argil::control_point_box(face).diagonal();
  argil::test::SpherePress p;
  p.uv = {0.5 * (face.domain_start(argil::Direction::u) + face.domain_end(argil::Direction::u)),
          0.5 * (face.domain_start(argil::Direction::v) + face.domain_end(argil::Direction::v))};
  p.radius = 0.1 * size;
  p.depth = 0.3 * p.radius;
  p.approach = 2.0 * p.radius;  // start clear of a face that curves towards the tool
  p.approach_time = 0.02;
  p.press_time = 0.1;
  p.release_time = 0.05;
  p.options.tolerance = 1e-3 * p.radius;
  p.material = m;
  p.samples = 17;
  p.check_every = 50;
  return p;
}

/// Presses face `index` of `file`; returns what failed, empty when nothing did.
std::string press_face(const std::string& file, std::size_t index, const BSplineSurface& face,
                       const argil::MaterialPreset& preset) {
  const argil::test::SpherePress p = press_for(face, preset.material);
  const argil::test::PressOutcome r = argil::test::press_sphere(face, p);
  const std::string where =
      file + " face " + std::to_string(index) + " " + std::string(preset.name) + ": ";
  if (!r.error.empty()) return where + r.error;
  if (!r.finite) return where + "not finite";
  // The tool's reach, as for the named plates: how deep the device's sphere
  // reaches into the rest face, plus its radius.
  const double reach = r.device_penetration + p.radius;
  if (!(r.max_control_move <= reach))
    return where + "control point moved " + std::to_string(r.max_control_move) + " mm, reach " +
           std::to_string(reach) + " mm";
  if (!(r.normal_turn <= r.turn_bound))
    return where + "normal turned " + std::to_string(r.normal_turn) + " rad, bound " +
           std::to_string(r.turn_bound) + " rad for a " + std::to_string(r.displacement) +
           " mm move";
  if (!(r.energy_rise <= 1e-12))
    return where + "energy rose by " + std::to_string(r.energy_rise) + " of " +
           std::to_string(r.energy_at_release) + " mJ after release";
  return "";
}

#ifndef ARGIL_REAL_FACE_STRIDE
#define ARGIL_REAL_FACE_STRIDE 1
#endif
/// 1: every face; the sanitizer build presses every fourth (tests/io/CMakeLists.txt).
constexpr std::size_t kFaceStride = ARGIL_REAL_FACE_STRIDE;

/// Presses every face of `file` (every kFaceStride-th) with clay, and every
/// fifth of those with the preset after clay in turn.
void press_every_face(const std::string& file) {
  const auto model = argil::io::read_model(argil::test::shared_data(file));
  INFO(model.status().message);
  REQUIRE(model.ok());
  const std::vector<argil::MaterialPreset>& presets = argil::material_presets();
  REQUIRE(presets.front().name == "clay");
  std::vector<std::string> failures;
  int presses = 0;
  const auto& faces = model.value().faces;
  for (std::size_t k = 0; k < faces.size(); k += kFaceStride) {
    std::vector<std::size_t> which{0};
    if ((k / kFaceStride) % 5 == 0) which.push_back(1 + (k / 5) % (presets.size() - 1));
    for (const std::size_t m : which) {
      ++presses;
      if (std::string f = press_face(file, k, faces[k].surface, presets[m]); !f.empty())
        failures.push_back(std::move(f));
    }
  }
  CAPTURE(faces.size(), presses, failures.size());
  std::string all;  // the first 20
  for (std::size_t i = 0; i < std::min<std::size_t>(failures.size(), 20); ++i)
    all += failures[i] + "\n";
  INFO(all);
  CHECK(failures.empty());
}

}  // namespace

TEST_CASE("real faces pressed: screw.step", "[deformation][real_faces]") {
  press_every_face("screw.step");
}

TEST_CASE("real faces pressed: bearing.iges", "[deformation][real_faces]") {
  press_every_face("bearing.iges");
}

// Clay flows up to 7 mm deep under a 15 mm sphere here: the normals reach
// the slope of the sphere's own imprint (normal_turn_bound).
TEST_CASE("real faces pressed: surf114.igs", "[deformation][real_faces]") {
  press_every_face("surf114.igs");
}

TEST_CASE("real faces pressed: as1-oc-214.stp", "[deformation][real_faces]") {
  press_every_face("as1-oc-214.stp");
}

// Left out under the sanitizers (a minute there at every sixteenth face): the
// four other files are pressed there.
TEST_CASE("real faces pressed: 11752.stp", "[deformation][real_faces][slow]") {
  press_every_face("11752.stp");
}

TEST_CASE("every preset is accepted on every face of bearing.iges and on a 1 m panel",
          "[deformation][real_faces]") {
  const auto model = argil::io::read_model(argil::test::shared_data("bearing.iges"));
  REQUIRE(model.ok());
  std::vector<BSplineSurface> faces;
  for (const argil::io::FaceRecord& f : model.value().faces) faces.push_back(f.surface);
  REQUIRE(faces.size() == 213);
  BSplineSurface panel;
  panel.degree = {3, 3};
  panel.knots = {argil::test::piece_knots(3, 5, 1), argil::test::piece_knots(3, 5, 1)};
  const Eigen::VectorXd g = argil::greville_abscissae(3, panel.knots[0]);
  panel.control_points.resize(g.size() * g.size(), 3);
  for (Eigen::Index i = 0; i < g.size(); ++i)
    for (Eigen::Index j = 0; j < g.size(); ++j)
      panel.control_points.row(panel.pole_index(static_cast<int>(i), static_cast<int>(j)))
          << 1000.0 * g[i],
          1000.0 * g[j], 30.0 * std::sin(3.0 * g[i]) * g[j];
  faces.push_back(panel);
  // Per preset: how many faces refuse it, and the first refusal.
  argil::OperatorCache cache;
  for (const argil::MaterialPreset& preset : argil::material_presets()) {
    int refused = 0;
    std::string first;
    for (std::size_t k = 0; k < faces.size(); ++k) {
      const auto body = argil::DeformableBody::create(faces[k], preset.material, {}, cache);
      if (body.ok()) continue;
      if (refused++ == 0)
        first = (k + 1 == faces.size() ? std::string("1 m panel") : "face " + std::to_string(k)) +
                " (" + std::to_string(argil::control_point_box(faces[k]).diagonal()) +
                " mm): " + body.status().message;
    }
    CAPTURE(preset.name, refused, faces.size(), first);
    CHECK(refused == 0);
  }
  // And the panel takes a press with every preset.
  for (const argil::MaterialPreset& preset : argil::material_presets()) {
    CAPTURE(preset.name);
    const std::string failure = press_face("1 m panel", 0, panel, preset);
    INFO(failure);
    CHECK(failure.empty());
  }
}

TEST_CASE("resolution independence: real faces and their 2x, 4x refinements",
          "[deformation][real_faces][resolution]") {
  // A bicubic piecewise-Bezier face (surf114.igs D3, 19 x 10 poles) as it
  // comes, and a rational cylinder (as1-oc-214.stp #624, 2 x 4 poles, so no
  // pole inside a press) with its spans halved twice first, pressed with clay
  // and with elastic clay: dent depth and peak force within 5%.
  struct RealFace {
    const char* file;
    std::size_t face;
    int halvings;  // to a net that resolves the press
  };
  argil::Material elastic = *argil::material_preset("clay");
  elastic.yield = std::numeric_limits<double>::infinity();
  for (const RealFace& f : {RealFace{"surf114.igs", 1, 0}, RealFace{"as1-oc-214.stp", 5, 2}}) {
    const auto model = argil::io::read_model(argil::test::shared_data(f.file));
    REQUIRE(model.ok());
    const BSplineSurface s =
        argil::test::halved_spans(model.value().faces.at(f.face).surface, f.halvings);
    for (const argil::Material& m : {*argil::material_preset("clay"), elastic}) {
      const argil::test::SpherePress p = press_for(s, m);
      const argil::test::PressOutcome base = argil::test::press_sphere(s, p);
      INFO(base.error);
      REQUIRE(base.error.empty());
      REQUIRE(base.dent > 0.0);
      for (const int times : {1, 2}) {
        const BSplineSurface r = argil::test::halved_spans(s, times);
        const argil::test::PressOutcome fine = argil::test::press_sphere(r, p);
        INFO(fine.error);
        REQUIRE(fine.error.empty());
        CAPTURE(f.file, f.face, m.yield, times, base.dent, fine.dent, base.peak_force,
                fine.peak_force);
        CHECK(std::abs(fine.dent - base.dent) <= 0.05 * base.dent);
        CHECK(std::abs(fine.peak_force - base.peak_force) <= 0.05 * base.peak_force);
      }
    }
  }
}
