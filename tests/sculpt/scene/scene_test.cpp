// Scenes: every field read, paths resolved against the scene's folder, and
// errors that name the field for each kind of bad input.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "argil/sculpt/scene/scene.hpp"
#include "argil/sculpt/script/script.hpp"

namespace argil::sculpt {
namespace {

const char* kGoodScene = R"({
  "format": "argil.scene", "version": 2,
  "units": {"length": "mm", "time": "s", "force": "N"},
  "tolerance": 0.05, "haptic_rate": 500,
  "coupling": {"stiffness": 2, "damping": 0.001, "max_force": 8},
  "models": [
    {"name": "hood", "file": "../surfaces/panel.json", "faces": [0],
     "material": {"preset": "clay", "thickness": 3, "damping": 0.02, "yield": 0.1},
     "friction": 0.45,
     "boundary": {"fixed_edges": ["u0", "v1"], "fixed_corners": true}},
    {"name": "frame", "file": "/abs/frame.step", "kind": "rigid", "friction": 0.15}
  ],
  "tools": [
    {"name": "ball", "type": "sphere", "radius": 20},
    {"name": "thumb", "type": "bspline", "file": "thumb.json", "face": 2},
    {"name": "pin", "type": "point"}
  ],
  "outputs": {"surfaces": ["step", "json"], "pictures": false},
  "script": "press.csv"
})";

TEST_CASE("a scene reads every field and resolves paths against its folder", "[scene]") {
  const Result<Scene> r = parse_scene(kGoodScene, "dent/scene.json", "/x/examples/dent");
  INFO(r.status().message);
  REQUIRE(r.ok());
  const Scene& s = r.value();
  CHECK(s.tolerance == 0.05);
  CHECK(s.haptic_rate == 500.0);
  CHECK(s.coupling.stiffness == 2.0);
  CHECK(s.coupling.max_force == 8.0);
  REQUIRE(s.models.size() == 2);
  CHECK(s.models[0].file == std::filesystem::path("/x/examples/surfaces/panel.json"));
  CHECK(s.models[0].faces == std::vector<int>{0});
  CHECK(s.models[0].deformable);
  CHECK(s.models[0].material.thickness == 3.0);
  CHECK(s.models[0].material.damping == 0.02);
  CHECK(s.models[0].material.yield == 0.1);
  CHECK(s.models[0].material.youngs_modulus == material_preset("clay")->youngs_modulus);
  CHECK(s.models[0].friction == 0.45);
  CHECK(s.models[0].boundary.fixed_u0);
  CHECK_FALSE(s.models[0].boundary.fixed_u1);
  CHECK(s.models[0].boundary.fixed_v1);
  CHECK(s.models[0].boundary.fixed_corners);
  CHECK(s.models[1].file == std::filesystem::path("/abs/frame.step"));
  CHECK_FALSE(s.models[1].deformable);
  CHECK(s.models[1].faces.empty());
  CHECK(s.models[1].friction == 0.15);  // a rigid model's own friction
  REQUIRE(s.tools.size() == 3);
  CHECK(s.tools[0].type == ToolType::sphere);
  CHECK(s.tools[0].radius == 20.0);
  CHECK(s.tools[1].type == ToolType::bspline);
  CHECK(s.tools[1].file == std::filesystem::path("/x/examples/dent/thumb.json"));
  CHECK(s.tools[1].face == 2);
  CHECK(s.tools[2].type == ToolType::point);
  CHECK(s.tool_index("pin") == 2);
  CHECK(s.tool_index("") == 0);
  CHECK(s.tool_index("nothing") == -1);
  CHECK(s.outputs.step);
  CHECK_FALSE(s.outputs.iges);
  CHECK_FALSE(s.outputs.pictures);
  CHECK(s.script == std::filesystem::path("/x/examples/dent/press.csv"));
  CHECK(s.version == 2);
  CHECK(s.warnings.empty());
}

TEST_CASE("a material given field by field defaults to elastic with 1e-3 s damping", "[scene]") {
  const Result<Scene> r = parse_scene(
      R"({"format": "argil.scene", "version": 2, "tolerance": 1,
          "models": [{"name": "m", "file": "m.json",
                      "material": {"density": 1200, "thickness": 4, "youngs_modulus": 2.5,
                                   "poisson_ratio": 0.25, "foundation_stiffness": 0.75}}],
          "tools": [{"name": "p", "type": "point"}]})",
      "s.json", ".");
  INFO(r.status().message);
  REQUIRE(r.ok());
  const Material& m = r.value().models[0].material;
  CHECK(m.density == 1200.0);
  CHECK(m.thickness == 4.0);
  CHECK(m.youngs_modulus == 2.5);
  CHECK(m.poisson_ratio == 0.25);
  CHECK(m.foundation_stiffness == 0.75);
  CHECK(m.damping == 1e-3);
  CHECK(std::isinf(m.yield));
  CHECK(r.value().models[0].friction == 0.3);
  CHECK(r.value().haptic_rate == 1000.0);
  CHECK_FALSE(r.value().resolution.has_value());  // derived from the tool
}

/// The good scene with one substitution (`from` must occur once).
std::string edited(const std::string& from, const std::string& to) {
  std::string s = kGoodScene;
  const std::size_t at = s.find(from);
  REQUIRE(at != std::string::npos);
  REQUIRE(s.find(from, at + 1) == std::string::npos);
  return s.replace(at, from.size(), to);
}

TEST_CASE("bad scenes give an error naming the field", "[scene][bad-input]") {
  const std::pair<std::string, std::string> cases[] = {
      {"", "empty file"},
      {"{\"format\": ", "not valid JSON"},
      {edited("\"argil.scene\"", "\"argil.surfaces\""), "format: expected \"argil.scene\""},
      {edited("\"version\": 2", "\"version\": 3"),
       "version: unknown schema version 3 (this build reads versions 1 to 2)"},
      {edited("\"version\": 2", "\"version\": 0"), "version: unknown schema version 0"},
      {edited("\"version\": 2", "\"version\": \"2\""), "version: expected an integer"},
      {edited("\"tolerance\": 0.05, ", ""), "tolerance: missing field"},
      {edited("\"tolerance\": 0.05", "\"tolerance\": -0.05"),
       "tolerance: must be > 0 mm, got -0.05 mm"},
      {edited("\"tolerance\": 0.05", "\"tolerance\": NaN"), "tolerance: NaN is not allowed"},
      {edited("\"tolerance\": 0.05", "\"tolerance\": null"), "tolerance: null where a number"},
      {edited("\"haptic_rate\": 500", "\"haptic_rate\": -1000"),
       "haptic_rate: must be > 0 Hz, got -1000 Hz"},
      {edited("\"haptic_rate\": 500", "\"haptic_rate\": 500, \"resolution\": -2"),
       "resolution: must be >= 0 mm, got -2 mm"},
      {edited("\"haptic_rate\": 500", "\"haptic_rate\": 500, \"resolution\": \"fine\""),
       "resolution: expected a number"},
      {edited("\"haptic_rate\": 500", "\"haptic_rate\": 0"),
       "haptic_rate: must be > 0 Hz, got 0 Hz"},
      {edited("\"haptic_rate\": 500", "\"haptic_rate\": 1e9"),
       "haptic_rate: must be at most 1e+05 Hz, got 1e+09 Hz"},
      {edited("\"length\": \"mm\"", "\"length\": \"inch\""), "units.length: must be \"mm\""},
      {edited("\"max_force\": 8", "\"max_force\": 0"),
       "coupling.max_force: must be in (0, 10000] N, got 0 N"},
      {edited("\"max_force\": 8", "\"max_force\": 2e4"),
       "coupling.max_force: must be in (0, 10000] N, got 20000 N"},
      {edited("\"stiffness\": 2", "\"stiffness\": 1e7"),
       "coupling.stiffness: must be in (0, 1e+06] N/mm, got 1e+07 N/mm"},
      {edited("\"damping\": 0.001", "\"damping\": -1"),
       "coupling.damping: must be in [0, 1000] N s/mm, got -1 N s/mm"},
      {edited("\"thickness\": 3", "\"thickness\": -3"),
       "models[0].material.thickness: must be in [1e-06, 10000] mm, got -3 mm"},
      {edited("\"thickness\": 3", "\"poisson_ratio\": 0.5"),
       "models[0].material.poisson_ratio: must be in [0, 0.5), got 0.5"},
      {edited("\"yield\": 0.1", "\"yield\": 0"),
       "models[0].material.yield: must be in [1e-09, inf] mm, got 0 mm"},
      {edited("\"yield\": 0.1", "\"yield\": \"soft\""),
       "models[0].material.yield: expected a number"},
      {edited("\"friction\": 0.45", "\"friction\": -0.3"),
       "models[0].friction: must be >= 0, got -0.3"},
      {edited("\"friction\": 0.45", "\"friction\": 11"),
       "models[0].friction: must be in [0, 10], got 11"},
      {edited("\"friction\": 0.15", "\"friction\": 12"),
       "models[1].friction: must be in [0, 10], got 12"},
      {edited("\"faces\": [0]", "\"faces\": [-1]"), "models[0].faces[0]: face index must be >= 0"},
      {edited("\"faces\": [0]", "\"faces\": [0, 0]"), "models[0].faces[1]: face 0 is listed twice"},
      {edited("\"faces\": [0]", "\"faces\": [1.5]"), "models[0].faces[0]: expected an integer"},
      {edited("\"faces\": [0]", "\"faces\": []"), "models[0].faces: expected \"all\""},
      {edited("\"kind\": \"rigid\"", "\"kind\": \"soft\""), "models[1].kind: expected"},
      {edited("\"fixed_edges\": [\"u0\", \"v1\"]", "\"fixed_edges\": [\"u2\"]"),
       "models[0].boundary.fixed_edges[0]: expected \"u0\""},
      {edited("\"fixed_corners\": true", "\"fixed_corners\": 1"),
       "models[0].boundary.fixed_corners: expected true or false"},
      {edited("\"file\": \"/abs/frame.step\", ", ""), "models[1].file: missing field"},
      {edited("\"name\": \"frame\"", "\"name\": \"hood\""),
       "models[1].name: \"hood\" is used twice"},
      {edited("\"name\": \"frame\"", "\"name\": \"../up\""), "models[1].name"},
      {edited("\"kind\": \"rigid\"", "\"kind\": \"rigid\", \"material\": {}"),
       "models[1].material: a rigid model has no material"},
      {edited("\"models\": [", "\"modls\": [], \"models\": ["), "modls: unknown field"},
      {edited("\"type\": \"sphere\"", "\"type\": \"torus\""),
       "tools[0].type: unknown tool type \"torus\" (known: sphere, bspline, point)"},
      {edited("\"type\": \"sphere\"", "\"type\": \"cube\""),
       "tools[0].type: unknown tool type \"cube\""},
      {edited("\"radius\": 20", "\"radius\": 0"), "tools[0].radius: must be > 0 mm, got 0 mm"},
      {edited("\"name\": \"ball\", \"type\": \"sphere\", \"radius\": 20",
              "\"name\": \"ball\", \"type\": \"sphere\""),
       "tools[0].radius: missing field"},
      {edited("\"face\": 2", "\"face\": -2"), "tools[1].face: face index must be >= 0"},
      {edited("\"file\": \"thumb.json\", ", ""), "tools[1].file: missing field"},
      {edited("\"name\": \"pin\", \"type\": \"point\"",
              "\"name\": \"pin\", \"type\": \"point\", \"radius\": 1"),
       "tools[2].radius: unknown field"},
      {edited("[\"step\", \"json\"]", "[\"stl\"]"), "outputs.surfaces[0]: expected \"step\""},
      {edited("\"pictures\": false", "\"pictures\": \"no\""), "outputs.pictures: expected true"},
      {edited("\"script\": \"press.csv\"", "\"script\": 3"), "script: expected a string"},
  };
  for (const auto& [text, expected] : cases) {
    const Result<Scene> r = parse_scene(text, "scene.json", ".");
    INFO(expected);
    REQUIRE_FALSE(r.ok());
    INFO(r.status().message);
    CHECK(r.status().message.rfind("scene.json: ", 0) == 0);
    CHECK(r.status().message.find(expected) != std::string::npos);
  }
}

TEST_CASE("the scene reader accepts exactly the coupling values validate() accepts",
          "[scene][bad-input]") {
  // The upper ends are inclusive; damping 0 is no damper.
  const std::pair<std::string, std::string> edges[] = {
      {"\"max_force\": 8", "\"max_force\": 1e4"},
      {"\"damping\": 0.001", "\"damping\": 0"},
  };
  for (const auto& [from, to] : edges) {
    const Result<Scene> r = parse_scene(edited(from, to), "scene.json", ".");
    INFO(to);
    REQUIRE(r.ok());
    CHECK(validate(r.value().coupling).ok());
  }
}

TEST_CASE("a scene without a deformable model or without tools is refused", "[scene][bad-input]") {
  const Result<Scene> rigid = parse_scene(
      R"({"format": "argil.scene", "version": 2, "tolerance": 1,
          "models": [{"name": "m", "file": "m.json", "kind": "rigid"}],
          "tools": [{"name": "p", "type": "point"}]})",
      "s.json", ".");
  REQUIRE_FALSE(rigid.ok());
  CHECK(rigid.status().message.find("models: no deformable model") != std::string::npos);
  const Result<Scene> no_tools = parse_scene(
      R"({"format": "argil.scene", "version": 2, "tolerance": 1,
          "models": [{"name": "m", "file": "m.json", "material": "clay"}],
          "tools": []})",
      "s.json", ".");
  REQUIRE_FALSE(no_tools.ok());
  CHECK(no_tools.status().message.find("tools: expected a non-empty array") != std::string::npos);
  const Result<Scene> missing = read_scene("/no/such/scene.json");
  REQUIRE_FALSE(missing.ok());
  CHECK(missing.status().message.find("/no/such/scene.json") != std::string::npos);
}

}  // namespace
}  // namespace argil::sculpt

namespace argil::sculpt {
namespace {

TEST_CASE("mutated scenes and scripts never crash the loaders", "[scene][bad-input]") {
  // Truncations and random byte changes of valid documents: every result is a
  // value or an error that starts with the source name.
  const std::string script_json = R"({"format": "argil.script", "version": 1, "tool": "ball",
    "keyframes": [{"t": 0, "position": [1, 2, 3], "orientation": [1, 0, 0, 0]},
                  {"t": 0.5, "position": [1, 2, -3], "event": "engage"},
                  {"t": 1, "position": [4, 2, -3], "event": "release"}]})";
  const std::string script_csv =
      "# argil.script version 1\n# tool: ball\nt,x,y,z,qw,qx,qy,qz,event\n0,1,2,3,1,0,0,0,\n"
      "0.5,1,2,-3,1,0,0,0,engage\n1,4,2,-3,1,0,0,0,release\n";
  std::mt19937 rng(12345);
  const std::string bytes = "{}[],:\"0123456789.eE-+ \nNaNaInfinity#tfnul";
  const std::string documents[] = {kGoodScene, script_json, script_csv};
  for (int d = 0; d < 3; ++d) {
    const std::string& doc = documents[d];
    for (int trial = 0; trial < 700; ++trial) {
      std::string text = doc;
      if (trial % 7 == 0) {
        text.resize(static_cast<std::size_t>(rng()) % text.size());
      } else {
        const int edits = 1 + static_cast<int>(rng() % 3);
        for (int e = 0; e < edits; ++e) {
          text[static_cast<std::size_t>(rng()) % text.size()] = bytes[rng() % bytes.size()];
        }
      }
      const std::string source = d == 0 ? "s.json" : (d == 1 ? "k.json" : "k.csv");
      const Status status = d == 0   ? parse_scene(text, source, ".").status()
                            : d == 1 ? parse_script_json(text, source).status()
                                     : parse_script_csv(text, source).status();
      if (!status.ok()) CHECK(status.message.rfind(source + ": ", 0) == 0);
    }
  }
}

}  // namespace
}  // namespace argil::sculpt
