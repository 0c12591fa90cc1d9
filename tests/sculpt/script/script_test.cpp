// Scripts: exact round trips through JSON and CSV, sampling at the haptic rate,
// strokes, recording, and errors that name the field.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <random>

#include "argil/sculpt/script/script.hpp"

namespace argil::sculpt {
namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

bool same_keyframe(const Keyframe& a, const Keyframe& b) {
  bool same = same_bits(a.t, b.t) && a.event == b.event && a.tool == b.tool;
  for (int c = 0; c < 3; ++c) same = same && same_bits(a.X_WD.p[c], b.X_WD.p[c]);
  for (int c = 0; c < 4; ++c) same = same && same_bits(a.X_WD.R.coeffs()[c], b.X_WD.R.coeffs()[c]);
  return same;
}

/// Keyframes with awkward doubles (no short decimal form) and random rotations.
Script random_script(unsigned seed, int count) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Script s;
  s.tool = "ball";
  double t = 0.0;
  bool engaged = false;
  for (int k = 0; k < count; ++k) {
    Keyframe f;
    f.t = t;
    t += 0.001 + 0.1 * std::abs(unit(rng));
    f.X_WD.p = Eigen::Vector3d(unit(rng), unit(rng), unit(rng)) * 123.456789;
    f.X_WD.R = Eigen::Quaterniond(unit(rng), unit(rng), unit(rng), unit(rng)).normalized();
    if (k % 3 == 1) {
      f.event = engaged ? ScriptEvent::release : ScriptEvent::engage;
      engaged = !engaged;
    }
    s.keyframes.push_back(f);
  }
  return s;
}

/// A press with the pin, the ball taken at 0.3 s, a press with it.
Script two_keyframes_for_tools() {
  Script s;
  s.tool = "pin";
  const double times[] = {0.0, 0.1, 0.2, 0.3, 0.4, 0.5};
  const ScriptEvent events[] = {ScriptEvent::none, ScriptEvent::engage, ScriptEvent::release,
                                ScriptEvent::tool, ScriptEvent::engage, ScriptEvent::release};
  for (int k = 0; k < 6; ++k) {
    Keyframe f;
    f.t = times[k];
    f.X_WD.p = Eigen::Vector3d(k, 0, 1);
    f.event = events[k];
    if (f.event == ScriptEvent::tool) f.tool = "ball";
    s.keyframes.push_back(f);
  }
  return s;
}

TEST_CASE("a script written as JSON or CSV reads back bit for bit", "[script]") {
  const Script original = random_script(7, 40);
  for (const bool csv : {false, true}) {
    const Result<Script> back = csv ? parse_script_csv(script_to_csv(original), "s.csv")
                                    : parse_script_json(script_to_json(original), "s.json");
    INFO((csv ? "csv" : "json") << ": " << back.status().message);
    REQUIRE(back.ok());
    CHECK(back.value().tool == original.tool);
    REQUIRE(back.value().keyframes.size() == original.keyframes.size());
    for (std::size_t k = 0; k < original.keyframes.size(); ++k) {
      CHECK(same_keyframe(back.value().keyframes[k], original.keyframes[k]));
    }
  }
}

TEST_CASE("a tool event reads and writes as tool:NAME in both formats; tools_held lists them",
          "[script]") {
  Script original = two_keyframes_for_tools();
  for (const bool csv : {false, true}) {
    const std::string text = csv ? script_to_csv(original) : script_to_json(original);
    CHECK(text.find("tool:ball") != std::string::npos);
    const Result<Script> back =
        csv ? parse_script_csv(text, "s.csv") : parse_script_json(text, "s.json");
    INFO(back.status().message);
    REQUIRE(back.ok());
    REQUIRE(back.value().keyframes.size() == original.keyframes.size());
    for (std::size_t k = 0; k < original.keyframes.size(); ++k)
      CHECK(same_keyframe(back.value().keyframes[k], original.keyframes[k]));
  }
  CHECK(tools_held(original) == std::vector<std::string>{"pin", "ball"});
  const ScriptSampler sampler(original, 1000.0);
  REQUIRE(sampler.commands().size() == 1);
  CHECK(sampler.commands()[0].event == ScriptEvent::tool);
  CHECK(sampler.commands()[0].tool == "ball");
  CHECK(sampler.commands()[0].tick == 300);
}

Script two_keyframes() {
  Script s;
  Keyframe a, b;
  a.t = 0.0;
  a.X_WD.p = Eigen::Vector3d(0, 0, 10);
  a.event = ScriptEvent::engage;
  b.t = 0.5;
  b.X_WD.p = Eigen::Vector3d(100, -50, 0);
  b.X_WD.R = Eigen::Quaterniond(Eigen::AngleAxisd(1.2, Eigen::Vector3d::UnitZ()));
  b.event = ScriptEvent::release;
  s.keyframes = {a, b};
  return s;
}

TEST_CASE("sampling is linear in position and slerp in orientation at t_k = k / rate", "[script]") {
  const ScriptSampler sampler(two_keyframes(), 1000.0);
  // Ticks 0..500 cover [0, 0.5] s.
  REQUIRE(sampler.tick_count() == 501);
  for (const long long k : {0LL, 1LL, 137LL, 250LL, 499LL, 500LL}) {
    const DeviceSample s = sampler.sample(k);
    CHECK(s.t == static_cast<double>(k) / 1000.0);
    const double alpha = s.t / 0.5;
    // Linear interpolation: rounding of one product and one sum (1e-12 of 100 mm).
    CHECK((s.X_WD.p - (Eigen::Vector3d(0, 0, 10) +
                       alpha * (Eigen::Vector3d(100, -50, 0) - Eigen::Vector3d(0, 0, 10))))
              .norm() < 1e-12);
    // Slerp about a fixed axis turns the angle linearly (rounding of acos/sin: 1e-12).
    const Eigen::AngleAxisd turn(s.X_WD.R);
    CHECK(std::abs(turn.angle() - 1.2 * alpha) < 1e-12);
    CHECK(std::abs(s.X_WD.R.norm() - 1.0) < 1e-14);
  }
  // The release at 0.5 s ends the stroke: tick 500 is not engaged.
  CHECK(sampler.sample(0).engaged);
  CHECK(sampler.sample(499).engaged);
  CHECK_FALSE(sampler.sample(500).engaged);
  REQUIRE(sampler.strokes().size() == 1);
  CHECK(sampler.strokes()[0].first_tick == 0);
  CHECK(sampler.strokes()[0].last_tick == 499);
}

TEST_CASE("strokes are the engaged intervals, before the first keyframe nothing is engaged",
          "[script]") {
  Script s;
  const double times[] = {0.1, 0.2, 0.3, 0.4, 0.45};
  const ScriptEvent events[] = {ScriptEvent::engage, ScriptEvent::release, ScriptEvent::none,
                                ScriptEvent::engage, ScriptEvent::none};
  for (int k = 0; k < 5; ++k) {
    Keyframe f;
    f.t = times[k];
    f.X_WD.p = Eigen::Vector3d(k, 0, 0);
    f.event = events[k];
    s.keyframes.push_back(f);
  }
  const ScriptSampler sampler(s, 100.0);  // 10 ms ticks; t_k = k / 100
  CHECK(sampler.tick_count() == 46);
  CHECK_FALSE(sampler.sample(9).engaged);
  CHECK(sampler.sample(9).X_WD.p == Eigen::Vector3d(0, 0, 0));
  REQUIRE(sampler.strokes().size() == 2);
  CHECK(sampler.strokes()[0].first_tick == 10);
  CHECK(sampler.strokes()[0].last_tick == 19);
  CHECK(sampler.strokes()[1].first_tick == 40);
  // Unreleased at the end: the stroke runs to the last tick.
  CHECK(sampler.strokes()[1].last_tick == 45);
}

TEST_CASE("a recorded sample stream replays bit for bit through CSV and JSON", "[script]") {
  const ScriptSampler original(random_script(11, 12), 1000.0);
  std::vector<DeviceSample> samples;
  for (long long k = 0; k < original.tick_count(); ++k) samples.push_back(original.sample(k));
  const Script recorded = record_script(samples, "ball");
  for (const bool csv : {false, true}) {
    const Result<Script> back = csv ? parse_script_csv(script_to_csv(recorded), "r.csv")
                                    : parse_script_json(script_to_json(recorded), "r.json");
    REQUIRE(back.ok());
    const ScriptSampler replay(back.value(), 1000.0);
    REQUIRE(replay.tick_count() == original.tick_count());
    bool identical = true;
    for (long long k = 0; k < replay.tick_count(); ++k) {
      const DeviceSample a = original.sample(k), b = replay.sample(k);
      identical = identical && a.engaged == b.engaged && same_bits(a.t, b.t);
      for (int c = 0; c < 3; ++c) identical = identical && same_bits(a.X_WD.p[c], b.X_WD.p[c]);
      for (int c = 0; c < 4; ++c) {
        identical = identical && same_bits(a.X_WD.R.coeffs()[c], b.X_WD.R.coeffs()[c]);
      }
    }
    CHECK(identical);
    CHECK(replay.strokes().size() == original.strokes().size());
  }
}

TEST_CASE("bad JSON scripts give an error naming the field", "[script][bad-input]") {
  const std::string head = R"({"format": "argil.script", "version": 1, "keyframes": [)";
  const std::pair<std::string, std::string> cases[] = {
      {"", "empty file"},
      {"{", "not valid JSON"},
      {R"({"version": 1, "keyframes": []})", "format: missing field"},
      {R"({"format": "argil.scene", "version": 1, "keyframes": []})", "format: expected"},
      {R"({"format": "argil.script", "version": 2, "keyframes": []})", "version: unknown schema"},
      {head + "]}", "keyframes: no keyframes"},
      {head + R"({"t": 0}]})", "keyframes[0].position: missing field"},
      {head + R"({"t": "zero", "position": [0,0,0]}]})", "keyframes[0].t: expected a number"},
      {head + R"({"t": NaN, "position": [0,0,0]}]})", "keyframes[0].t: NaN is not allowed"},
      {head + R"({"t": 0, "position": [0,0,1e999]}]})", "keyframes[0].position[2]: 1e999"},
      {head + R"({"t": 0, "position": [0,0]}]})", "keyframes[0].position: expected an array of 3"},
      {head + R"({"t": -1, "position": [0,0,0]}]})", "keyframes[0].t: time must be >= 0"},
      {head + R"({"t": 1, "position": [0,0,0]}, {"t": 0.5, "position": [0,0,0]}]})",
       "keyframes[1].t: time 0.5 s is not after"},
      {head + R"({"t": 1, "position": [0,0,0]}, {"t": 1, "position": [0,0,0]}]})",
       "keyframes[1].t"},
      {head + R"({"t": 0, "position": [0,0,0], "orientation": [0,0,0,0]}]})",
       "keyframes[0].orientation: not a unit quaternion"},
      {head + R"({"t": 0, "position": [0,0,0], "orientation": [2,0,0,0]}]})",
       "keyframes[0].orientation: not a unit quaternion (w, x, y, z): norm 2"},
      {head + R"({"t": 0, "position": [0,0,0], "orientation": [1,0,0]}]})",
       "keyframes[0].orientation: expected an array of 4"},
      {head + R"({"t": 0, "position": [0,0,0], "event": "push"}]})", "keyframes[0].event"},
      {head + R"({"t": 0, "position": [0,0,0], "event": "release"}]})",
       "keyframes[0].event: release while not engaged"},
      {head + R"({"t": 0, "position": [0,0,0], "event": "engage"},)" +
           R"({"t": 1, "position": [0,0,0], "event": "engage"}]})",
       "keyframes[1].event: engage while already engaged"},
      {head + R"({"t": 0, "position": [0,0,0], "event": "engage"},)" +
           R"({"t": 1, "position": [0,0,0], "event": "tool:ball"}]})",
       "keyframes[1].event: tool while engaged: release first"},
      {head + R"({"t": 0, "position": [0,0,0], "event": "tool:"}]})",
       "keyframes[0].event: expected engage, release, undo, redo, tool:NAME"},
      {head + R"({"t": 0, "position": [0,0,0], "event": "tool:two words"}]})",
       "keyframes[0].event: tool name must be one word"},
      {head + R"({"t": 0, "position": [0,0,0], "speed": 3}]})",
       "keyframes[0].speed: unknown field"},
      {R"({"format": "argil.script", "version": 1, "keyframes": {}})",
       "keyframes: expected an array"},
      {R"([1, 2])", "(root): expected an object"},
  };
  for (const auto& [text, expected] : cases) {
    const Result<Script> r = parse_script_json(text, "bad.json");
    INFO(text);
    REQUIRE_FALSE(r.ok());
    INFO(r.status().message);
    CHECK(r.status().message.rfind("bad.json: ", 0) == 0);
    CHECK(r.status().message.find(expected) != std::string::npos);
  }
}

TEST_CASE("bad CSV scripts give an error naming the line and column", "[script][bad-input]") {
  const std::string header = "t,x,y,z,qw,qx,qy,qz,event\n";
  const std::pair<std::string, std::string> cases[] = {
      {"", "empty file"},
      {"time,x,y,z\n0,0,0,0\n", "line 1: expected the header"},
      {header + "0,0,0,0,1,0,0\n", "line 2: expected 8 or 9 columns"},
      {header + "0,0,abc,0,1,0,0,0\n", "line 2: y: expected a number, got 'abc'"},
      {header + "0,0,0,nan,1,0,0,0\n", "line 2: z: 'nan' is not allowed"},
      {header + "0,0,0,inf,1,0,0,0\n", "line 2: z: 'inf' is not allowed"},
      {header + "0,0,0,0,,0,0,0\n", "line 2: qw: empty cell"},
      {header + "0,0,0,0,0,0,0,0\n", "line 2: qw..qz: not a unit quaternion"},
      {header + "0,0,0,0,1,0,0,0,press\n", "line 2: event"},
      {header + "0,0,0,0,1,0,0,0,engage\n1,0,0,0,1,0,0,0,tool:ball\n",
       "tool while engaged: release first"},
      {header + "0.5,0,0,0,1,0,0,0\n\n0.25,0,0,0,1,0,0,0\n", "line 4: t: time 0.25 s is not after"},
      {"# argil.script version 3\n" + header + "0,0,0,0,1,0,0,0\n",
       "line 1: unknown schema version 3"},
      {"# only a comment\n", "missing the header"},
      {header, "keyframes: no keyframes"},
  };
  for (const auto& [text, expected] : cases) {
    const Result<Script> r = parse_script_csv(text, "bad.csv");
    INFO(text);
    REQUIRE_FALSE(r.ok());
    INFO(r.status().message);
    CHECK(r.status().message.rfind("bad.csv: ", 0) == 0);
    CHECK(r.status().message.find(expected) != std::string::npos);
  }
}

TEST_CASE("read_script refuses unknown extensions and names missing files", "[script][bad-input]") {
  const Result<Script> ext = read_script("stroke.txt");
  REQUIRE_FALSE(ext.ok());
  CHECK(ext.status().message.find("stroke.txt") != std::string::npos);
  const Result<Script> missing = read_script("/no/such/folder/stroke.csv");
  REQUIRE_FALSE(missing.ok());
  CHECK(missing.status().message.find("/no/such/folder/stroke.csv") != std::string::npos);
}

TEST_CASE("fuzz regression scripts are refused with a message naming the field",
          "[script][bad-input]") {
  const auto crash = read_script(std::filesystem::path(ARGIL_SOURCE_DIR) / "tests" / "data" /
                                 "fuzz-regressions-sculpt" / "script-invalid-utf8-tool.csv");
  REQUIRE_FALSE(crash.ok());
  CHECK(crash.status().message.find("tool") != std::string::npos);
  CHECK(crash.status().message.find("UTF-8") != std::string::npos);
}

TEST_CASE("tool names are one word of valid UTF-8 in both formats", "[script][bad-input]") {
  const std::string frame = "t,x,y,z,qw,qx,qy,qz,event\n0,0,0,0,1,0,0,0,\n";
  // Valid: ASCII and multibyte UTF-8 names round trip through both formats.
  for (const std::string name : {"ball", "Daumen-\xc3\xa4", "\xe2\x9c\x8b"}) {
    const auto csv = parse_script_csv("# tool: " + name + "\n" + frame, "s.csv");
    REQUIRE(csv.ok());
    CHECK(csv.value().tool == name);
    const auto json = parse_script_json(script_to_json(csv.value()), "s.json");
    REQUIRE(json.ok());
    CHECK(json.value().tool == name);
    CHECK(parse_script_csv(script_to_csv(json.value()), "again.csv").value().tool == name);
  }
  // Refused: invalid bytes, overlong forms, surrogates, two words, control characters.
  for (const std::string name : {"\xd7\xd7", "\xc0\xaf", "\xed\xa0\x80", "a\x01b"}) {
    const auto csv = parse_script_csv("# tool: " + name + "\n" + frame, "s.csv");
    REQUIRE_FALSE(csv.ok());
    CHECK(csv.status().message.find("tool") != std::string::npos);
  }
  CHECK_FALSE(parse_script_csv("# tool: two words\n" + frame, "s.csv").ok());
  const auto spaced = parse_script_json(
      R"({"format": "argil.script", "version": 1, "tool": "two words",
          "keyframes": [{"t": 0, "position": [0, 0, 0], "orientation": [1, 0, 0, 0]}]})",
      "s.json");
  REQUIRE_FALSE(spaced.ok());
  CHECK(spaced.status().message.find("tool") != std::string::npos);
  Script bad;
  bad.tool = "tab\there";
  bad.keyframes.resize(1);
  CHECK_FALSE(validate(bad).ok());
}

}  // namespace
}  // namespace argil::sculpt

namespace argil::sculpt {

TEST_CASE("a command less than a tick after a release waits for the tick after the release",
          "[script]") {
  Script s;
  const double times[] = {0.0, 0.005, 0.0101, 0.0103, 0.02};
  const ScriptEvent events[] = {ScriptEvent::none, ScriptEvent::engage, ScriptEvent::release,
                                ScriptEvent::tool, ScriptEvent::none};
  for (int k = 0; k < 5; ++k) {
    Keyframe f;
    f.t = times[k];
    f.event = events[k];
    if (f.event == ScriptEvent::tool) f.tool = "ball";
    s.keyframes.push_back(f);
  }
  const ScriptSampler sampler(s, 1000.0);
  // Tick 10 (t = 0.010) is still engaged, tick 11 is the release: the tool
  // change comes before tick 12.
  CHECK(sampler.sample(10).engaged);
  CHECK_FALSE(sampler.sample(11).engaged);
  REQUIRE(sampler.commands().size() == 1);
  CHECK(sampler.commands()[0].tick == 12);
}

TEST_CASE("record_script keeps a tool taken before the first tick on the first keyframe",
          "[script]") {
  std::vector<DeviceSample> samples(3);
  for (int k = 0; k < 3; ++k) {
    samples[static_cast<std::size_t>(k)].tick = k;
    samples[static_cast<std::size_t>(k)].t = k / 1000.0;
  }
  const std::vector<ScriptSampler::Command> commands = {{0, ScriptEvent::tool, 0, "ball"}};
  const Script recorded = record_script(samples, "pin", commands);
  CHECK(recorded.tool == "pin");
  REQUIRE(recorded.keyframes.front().event == ScriptEvent::tool);
  CHECK(recorded.keyframes.front().tool == "ball");
  CHECK(tools_held(recorded) == std::vector<std::string>{"pin", "ball"});
  const ScriptSampler sampler(recorded, 1000.0);
  REQUIRE(sampler.commands().size() == 1);
  CHECK(sampler.commands()[0].tick == 0);
  CHECK_FALSE(validate(Script{"pin", {Keyframe{0.0, {}, ScriptEvent::tool, "a,b"}}}).ok());
}

}  // namespace argil::sculpt
