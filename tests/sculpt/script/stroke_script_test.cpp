// Scripts generated from (u, v) on a real face: the device follows the
// surface at the depth (checked against the cylinder's own geometry), moves
// at the speed, engages and releases once, and bad places are refused.
#include <catch2/catch.hpp>
#include <cmath>

#include "argil/core/geometry/evaluate.hpp"
#include "argil/io/files/model_files.hpp"
#include "argil/sculpt/script/stroke_script.hpp"

using argil::sculpt::Keyframe;
using argil::sculpt::ScriptEvent;
using argil::sculpt::StrokeRequest;

namespace {

argil::io::Model screw() {
  argil::Result<argil::io::Model> model =
      argil::io::read_model(std::string(ARGIL_SOURCE_DIR) + "/tests/data/screw.step");
  REQUIRE(model.ok());
  return std::move(model.value());
}

/// Face 7 of screw.step is a cylinder of radius 5 mm about a z axis (u turns
/// round it from 0 to 2 pi): the axis passes midway between opposite points.
double from_axis(const Eigen::Vector3d& p) {
  static const argil::io::Model model = screw();
  const argil::BSplineSurface& s = model.faces[7].surface;
  static const Eigen::Vector3d axis =
      0.5 * (argil::evaluate(s, 0.0, 0.0) + argil::evaluate(s, M_PI, 0.0));
  return std::hypot(p.x() - axis.x(), p.y() - axis.y());
}

}  // namespace

TEST_CASE("a drag on the screw's cylinder keeps the tool at its depth, at its speed") {
  const argil::io::Model model = screw();
  StrokeRequest r;
  r.uv = {{2.5, 0.0}, {3.8, 0.0}, {3.8, 5.0}};
  r.depth_mm = 0.8;
  r.speed_mm_s = 12.0;
  r.approach_mm = 6.0;
  r.tool_offset_mm = 3.0;  // a sphere of radius 3
  r.tool = "ball";
  const argil::Result<argil::sculpt::Script> script =
      argil::sculpt::stroke_script(model.faces[7], r, "screw face 7", 0.75);
  REQUIRE(script.ok());
  const std::vector<Keyframe>& k = script.value().keyframes;
  CHECK(script.value().tool == "ball");
  int engages = 0, releases = 0;
  std::size_t engaged_at = 0, released_at = 0;
  for (std::size_t i = 0; i < k.size(); ++i) {
    if (k[i].event == ScriptEvent::engage) ++engages, engaged_at = i;
    if (k[i].event == ScriptEvent::release) ++releases, released_at = i;
    if (i == 0) continue;
    const double dt = k[i].t - k[i - 1].t;
    REQUIRE(dt > 0.0);
    CHECK((k[i].X_WD.p - k[i - 1].X_WD.p).norm() / dt <= 12.0 * (1.0 + 1e-9));
  }
  REQUIRE(engages == 1);
  REQUIRE(releases == 1);
  // Outside the cylinder: start and end approach + radius above it, engage
  // and release a tenth of the approach above; in between, at the depth.
  CHECK(from_axis(k.front().X_WD.p) == Approx(5.0 + 3.0 + 6.0).epsilon(1e-9));
  CHECK(from_axis(k.back().X_WD.p) == Approx(5.0 + 3.0 + 6.0).epsilon(1e-9));
  CHECK(from_axis(k[engaged_at].X_WD.p) == Approx(5.0 + 3.0 + 0.6).epsilon(1e-9));
  CHECK(from_axis(k[released_at].X_WD.p) == Approx(5.0 + 3.0 + 0.6).epsilon(1e-9));
  REQUIRE(released_at > engaged_at + 3);
  for (std::size_t i = engaged_at + 1; i < released_at; ++i) {
    INFO("keyframe " << i);
    CHECK(from_axis(k[i].X_WD.p) == Approx(5.0 + 3.0 - 0.8).epsilon(1e-9));
    if (i > engaged_at + 1) CHECK((k[i].X_WD.p - k[i - 1].X_WD.p).norm() <= 0.75);
  }
  // It went round the cylinder by 1.3 rad, then 5 mm along it (z is v here).
  const Eigen::Vector3d last = k[released_at - 1].X_WD.p;
  CHECK(std::abs(last.z() - k[engaged_at + 1].X_WD.p.z()) == Approx(5.0).epsilon(1e-6));
}

TEST_CASE("a press rests at its depth for the hold time") {
  const argil::io::Model model = screw();
  StrokeRequest r;
  r.uv = {{3.14159, 0.0}};
  r.depth_mm = 1.0;
  r.hold_s = 0.25;
  r.tool_offset_mm = 3.0;
  const argil::Result<argil::sculpt::Script> script =
      argil::sculpt::stroke_script(model.faces[7], r, "screw face 7", 0.75);
  REQUIRE(script.ok());
  const std::vector<Keyframe>& k = script.value().keyframes;
  REQUIRE(k.size() == 6);
  CHECK(from_axis(k[2].X_WD.p) == Approx(7.0).epsilon(1e-9));
  CHECK(k[3].X_WD.p == k[2].X_WD.p);
  CHECK(k[3].t - k[2].t == Approx(0.25));
}

TEST_CASE("stroke scripts refuse places off the face and bad settings, naming them") {
  const argil::io::Model model = screw();
  StrokeRequest r;
  r.tool_offset_mm = 3.0;
  const auto message = [&](const argil::io::FaceRecord& face) {
    const auto s = argil::sculpt::stroke_script(face, r, "screw face N", 0.75);
    REQUIRE_FALSE(s.ok());
    return s.status().message;
  };
  // Face 9 is the bottom disc: its square domain's corner holds no material.
  r.uv = {{-4.0, -6.0}};
  CHECK_THAT(message(model.faces[9]), Catch::Contains("outside the face's trims"));
  r.uv = {{3.0, 99.0}};
  CHECK_THAT(message(model.faces[7]), Catch::Contains("outside the surface's domain"));
  // A drag whose straight (u, v) line leaves the disc is refused too.
  r.uv = {{-2.0, -2.0}, {2.0, -6.0}};
  CHECK_THAT(message(model.faces[9]), Catch::Contains("outside the face's trims"));
  r.uv = {{3.0, 0.0}};
  r.depth_mm = 0.0;
  CHECK_THAT(message(model.faces[7]), Catch::Contains("depth 0 mm must be positive"));
  r.depth_mm = 1.0;
  r.speed_mm_s = -1.0;
  CHECK_THAT(message(model.faces[7]), Catch::Contains("speed -1 mm/s"));
}
