// Refinement of a session's faces for the tool (docs/deformation.md,
// Refinement): a 2 x 2 plane the script presses is elevated and refined
// before the first tick, exactly (the same surface), and then dents where the
// sphere presses instead of moving as a whole; a face the path never comes
// near, a point tool, and resolution 0 refine nothing.
#include <unistd.h>
#include <catch2/catch.hpp>
#include <random>

#include "argil/core/geometry/evaluate.hpp"
#include "argil/io/json/json_format.hpp"
#include "argil/sculpt/scene/scene.hpp"
#include "argil/sculpt/script/script.hpp"
#include "argil/sculpt/session/session.hpp"

namespace argil::sculpt {
namespace {

/// A flat degree-1 plane, 2 x 2 control points, `size` mm square at height z.
BSplineSurface plane(double size, double x0, double z) {
  BSplineSurface s;
  s.degree = {1, 1};
  s.knots = {Eigen::Vector4d(0, 0, 1, 1), Eigen::Vector4d(0, 0, 1, 1)};
  s.control_points.resize(4, 3);
  s.control_points << x0, 0, z, x0, size, z, x0 + size, 0, z, x0 + size, size, z;
  return s;
}

/// Two planes (a 40 mm one at the origin, a second 200 mm along x) written to
/// the temp folder, and a scene with a 4 mm sphere (or a point) over them.
Scene scene_with(const char* tool, const char* resolution) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path();
  const std::filesystem::path file =
      dir / ("argil-refine-planes-" + std::to_string(::getpid()) + ".json");
  io::Model model;
  for (const double x0 : {0.0, 200.0}) {
    io::FaceRecord face;
    face.surface = plane(40.0, x0, 0.0);
    model.faces.push_back(face);
  }
  REQUIRE(io::write_json(model, file).ok());
  const std::string text = std::string(R"({"format": "argil.scene", "version": 2,
      "tolerance": 0.01, )") +
                           resolution + R"(
      "models": [{"name": "planes", "file": ")" +
                           file.string() + R"(", "material": "clay",
                  "boundary": {"fixed_edges": ["u0", "u1", "v0", "v1"]}}],
      "tools": [)" + tool + "]}";
  const Result<Scene> scene = parse_scene(text, "refine-scene.json", dir);
  INFO(scene.status().message);
  REQUIRE(scene.ok());
  return scene.value();
}

constexpr const char* kSphere = R"({"name": "ball", "type": "sphere", "radius": 4})";

/// Down onto (20, 20) from 10 mm above, 1 mm into the plane, held, lifted.
Script press_script() {
  Script s;
  const auto at = [](double t, double z, ScriptEvent e) {
    Keyframe k;
    k.t = t;
    k.X_WD.p = Eigen::Vector3d(20.0, 20.0, z);
    k.event = e;
    return k;
  };
  s.keyframes = {at(0.0, 14.0, ScriptEvent::engage), at(0.2, 3.0, ScriptEvent::none),
                 at(0.4, 3.0, ScriptEvent::none)};
  return s;
}

std::vector<std::vector<Eigen::Vector3d>> path_of(const Script& s) { return engaged_paths(s); }

}  // namespace

TEST_CASE("a plane the script presses is refined exactly before the first tick, then dents",
          "[session][refinement]") {
  const Scene scene = scene_with(kSphere, "");
  const Script script = press_script();
  Result<Session> created = Session::create(scene, "", path_of(script));
  INFO(created.status().message);
  REQUIRE(created.ok());
  Session session = std::move(created).value();
  // Only the pressed plane; the one 200 mm away is left as it is.
  REQUIRE(session.refinements().size() == 1);
  const FaceRefinement& r = session.refinements()[0];
  CHECK(r.face == 0);
  CHECK(r.report.degree_before == std::array<int, 2>{1, 1});
  CHECK(r.report.degree_after == std::array<int, 2>{3, 3});
  // Default resolution: the sphere's radius (3 control points across it).
  CHECK(r.report.resolution == 4.0);
  CHECK(r.report.count_after[0] >= 12);
  CHECK(r.report.count_after[1] >= 12);
  CHECK_THAT(refinement_text(r),
             Catch::Contains("degree 1 x 1 -> 3 x 3") && Catch::Contains("spans <= 4 mm"));
  const BSplineSurface original = plane(40.0, 0.0, 0.0);
  const BSplineSurface refined = session.current_faces(0).faces[0].surface;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int k = 0; k < 400; ++k) {
    const double u = unit(rng), v = unit(rng);
    CHECK((evaluate(refined, u, v) - evaluate(original, u, v)).norm() <= 1e-12 * 40.0);
  }
  CHECK(session.current_faces(0).faces[1].surface.control_points ==
        plane(40.0, 200.0, 0.0).control_points);

  // The press dents under the sphere: the surface there sinks by a good part
  // of the press depth while points 12 mm away (three radii) barely move.
  const ScriptSampler sampler(script, scene.haptic_rate);
  for (long long k = 0; k < sampler.tick_count(); ++k) {
    const Result<TickReport> t = session.step(sampler.sample(k));
    INFO(t.status().message);
    REQUIRE(t.ok());
  }
  const BSplineSurface pressed = session.current_faces(0).faces[0].surface;
  const double under = -evaluate(pressed, 0.5, 0.5).z();
  const double beside = std::abs(evaluate(pressed, 0.8, 0.5).z());
  CAPTURE(under, beside);
  CHECK(under > 0.2);
  CHECK(beside < 0.1 * under);
}

TEST_CASE("only where the tool is engaged: a free move over a plane refines nothing",
          "[session][refinement]") {
  // Over the far plane free, down onto the near one engaged.
  Script s = press_script();
  Keyframe over;
  over.X_WD.p = Eigen::Vector3d(220.0, 20.0, 5.0);
  s.keyframes.insert(s.keyframes.begin(), over);
  s.keyframes[1].t = 0.5;
  s.keyframes[2].t = 0.7;
  s.keyframes[3].t = 0.9;
  REQUIRE(validate(s).ok());
  const std::vector<std::vector<Eigen::Vector3d>> paths = engaged_paths(s);
  REQUIRE(paths.size() == 1);
  CHECK(paths[0].size() == 3);
  Result<Session> created = Session::create(scene_with(kSphere, ""), "", paths);
  REQUIRE(created.ok());
  REQUIRE(created.value().refinements().size() == 1);
  CHECK(created.value().refinements()[0].face == 0);
}

TEST_CASE("resolution 0 and a point tool refine nothing", "[session][refinement]") {
  const Script script = press_script();
  for (const auto& [tool, resolution] : {std::pair{kSphere, R"("resolution": 0,)"},
                                         std::pair{R"({"name": "pin", "type": "point"})", ""}}) {
    const Scene scene = scene_with(tool, resolution);
    Result<Session> created = Session::create(scene, "", path_of(script));
    REQUIRE(created.ok());
    CHECK(created.value().refinements().empty());
    CHECK(created.value().current_faces(0).faces[0].surface.control_points.rows() == 4);
  }
  // An explicit resolution on a point tool refines.
  const Scene pin = scene_with(R"({"name": "pin", "type": "point"})", R"("resolution": 5,)");
  Result<Session> created = Session::create(pin, "", path_of(script));
  REQUIRE(created.ok());
  REQUIRE(created.value().refinements().size() == 1);
  CHECK(created.value().refinements()[0].report.resolution == 5.0);
}

}  // namespace argil::sculpt
