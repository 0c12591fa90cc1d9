// Switching tools at a release: a script's `tool:NAME` event puts another of
// the scene's tools in the device's hand between strokes. The stroke after it
// is made with that tool; undo and redo replay each stroke with the tool it
// was made with; a run stopped after the switch resumes to the same bits, and
// recorded.csv replays it.
#include <catch2/catch.hpp>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>

#include "argil/core/geometry/evaluate.hpp"
#include "argil/io/files/model_files.hpp"
#include "argil/sculpt/run/session_runner.hpp"
#include "argil/sculpt/session/session.hpp"
#include "argil/sculpt/view/session_replay.hpp"
#include "run_checks.hpp"

namespace argil::sculpt {
namespace {

namespace fs = std::filesystem;
using test::poles_of;
using test::run_ok;
using test::same_bits;

const fs::path kWork = fs::path(ARGIL_BINARY_DIR) / "tool-switch-test";
const fs::path kScene = fs::path(ARGIL_SOURCE_DIR) / "tests/data/sculpt/two_tools.json";

/// A press of the pin, then `between` (CSV lines), then a second press at
/// x = 100, then `tail`.
fs::path script_with(const std::string& name, const std::string& between,
                     const std::string& tail = "0.45,100,20,10,1,0,0,0,\n") {
  fs::create_directories(kWork);
  const fs::path path = kWork / (name + ".csv");
  std::ofstream out(path, std::ios::binary);
  out << "# argil.script version 1\n"
         "# tool: pin\n"
         "t,x,y,z,qw,qx,qy,qz,event\n"
         "0,60,0,10,1,0,0,0,\n"
         "0.04,60,0,1,1,0,0,0,engage\n"
         "0.1,60,10,-4,1,0,0,0,\n"
         "0.17,60,20,5,1,0,0,0,release\n"
      << between
      << "0.24,100,0,1,1,0,0,0,engage\n"
         "0.3,100,10,-4,1,0,0,0,\n"
         "0.37,100,20,5,1,0,0,0,release\n"
      << tail;
  return path;
}

RunOptions options_for(const fs::path& script, const fs::path& out, bool fresh = true) {
  return test::json_run(kScene, script, out, fresh);
}

std::string text_of(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

TEST_CASE("the stroke after a tool event is made with that tool; recorded.csv replays it",
          "[run]") {
  const fs::path pinned = kWork / "pin-only";
  run_ok(options_for(script_with("pin-only", "0.2,100,0,10,1,0,0,0,\n"), pinned));
  const fs::path switched = kWork / "switched";
  const RunReport r =
      run_ok(options_for(script_with("switched", "0.2,100,0,10,1,0,0,0,tool:ball\n"), switched));
  CHECK(r.strokes == 2);
  // The ball (radius 4) pressed where the pin did: another dent.
  CHECK_FALSE(same_bits(poles_of(pinned / "plate.json"), poles_of(switched / "plate.json")));
  // The whole run with the ball from the start, the first press included,
  // differs too: the switch came after the first stroke.
  const std::string recorded = text_of(switched / "recorded.csv");
  CHECK(recorded.find(",tool:ball\n") != std::string::npos);
  CHECK(recorded.find("# tool: pin\n") != std::string::npos);
  run_ok(options_for(switched / "recorded.csv", kWork / "replayed"));
  CHECK(same_bits(poles_of(kWork / "replayed" / "plate.json"), poles_of(switched / "plate.json")));
  // The journal keeps the switch as its own record.
  CHECK(text_of(switched / "session.journal").find("\ntool 1 state=") != std::string::npos);
}

TEST_CASE("undo and redo replay each stroke with the tool it was made with", "[run]") {
  const fs::path switched = kWork / "undo-switched";
  run_ok(options_for(script_with("undo-switched", "0.2,100,0,10,1,0,0,0,tool:ball\n"), switched));
  // Undo the ball's press, go back to the pin, redo: the ball's press again.
  const fs::path redone = kWork / "redone";
  run_ok(options_for(script_with("redone", "0.2,100,0,10,1,0,0,0,tool:ball\n",
                                 "0.4,100,20,10,1,0,0,0,undo\n0.41,100,20,10,1,0,0,0,tool:pin\n"
                                 "0.42,100,20,10,1,0,0,0,redo\n0.45,100,20,10,1,0,0,0,\n"),
                     redone));
  CHECK(same_bits(poles_of(redone / "plate.json"), poles_of(switched / "plate.json")));
  // Undo both presses after the switch: the plate as read.
  const fs::path undone = kWork / "undone";
  run_ok(options_for(script_with("undone", "0.2,100,0,10,1,0,0,0,tool:ball\n",
                                 "0.4,100,20,10,1,0,0,0,undo\n0.41,100,20,10,1,0,0,0,undo\n"
                                 "0.45,100,20,10,1,0,0,0,\n"),
                     undone));
  // The plate as read, refined for the ball (exactly: the same surface).
  const Result<io::Model> original =
      io::read_model(fs::path(ARGIL_SOURCE_DIR) / "examples/groove/plate.json");
  const Result<io::Model> back = io::read_model(undone / "plate.json");
  REQUIRE(original.ok());
  REQUIRE(back.ok());
  const BSplineSurface& a = original.value().faces[0].surface;
  const BSplineSurface& b = back.value().faces[0].surface;
  double worst = 0.0;
  for (int i = 0; i <= 20; ++i) {
    for (int j = 0; j <= 20; ++j) {
      const double u = a.domain_start(Direction::u) +
                       (a.domain_end(Direction::u) - a.domain_start(Direction::u)) * i / 20.0;
      const double v = a.domain_start(Direction::v) +
                       (a.domain_end(Direction::v) - a.domain_start(Direction::v)) * j / 20.0;
      worst = std::max(worst, (evaluate(a, u, v) - evaluate(b, u, v)).norm());
    }
  }
  CHECK(worst < 1e-9);
}

TEST_CASE("a run stopped after a tool switch resumes to the same bits", "[run]") {
  const fs::path script = script_with("resume", "0.2,100,0,10,1,0,0,0,tool:ball\n");
  const fs::path whole = kWork / "resume-whole";
  run_ok(options_for(script, whole));
  for (const long long stop_at : {205LL, 300LL}) {
    const fs::path out = kWork / ("resume-" + std::to_string(stop_at));
    fs::remove_all(out);
    RunOptions stopping = options_for(script, out);
    stopping.progress_every = 1;
    stopping.on_progress = [stop_at](const RunProgress& p) {
      return p.ticks_done >= stop_at ? RunControl::stop : RunControl::proceed;
    };
    REQUIRE(run_ok(stopping).stopped);
    const RunReport resumed = run_ok(options_for(script, out, false));
    CHECK(resumed.start == RunStart::resumed);
    CHECK(same_bits(poles_of(out / "plate.json"), poles_of(whole / "plate.json")));
  }
}

TEST_CASE("a tool switch is refused during a stroke, for a tool not in the scene, and named",
          "[run]") {
  const Result<RunReport> unknown = run_session(
      options_for(script_with("unknown", "0.2,100,0,10,1,0,0,0,tool:chisel\n"), kWork / "unknown"));
  REQUIRE_FALSE(unknown.ok());
  CHECK_THAT(unknown.status().message,
             Catch::Contains("keyframes[4].event: tool \"chisel\" is not a tool of"));
  CHECK_FALSE(fs::exists(kWork / "unknown"));
  const Result<RunReport> engaged = run_session(options_for(
      script_with("engaged", "0.18,100,0,10,1,0,0,0,engage\n0.2,100,0,10,1,0,0,0,tool:ball\n"),
      kWork / "engaged"));
  REQUIRE_FALSE(engaged.ok());
  CHECK_THAT(engaged.status().message, Catch::Contains("tool while engaged: release first"));

  // The session itself refuses mid-stroke and unknown names, and keeps its tool.
  const Result<Scene> scene = read_scene(kScene);
  REQUIRE(scene.ok());
  Result<Session> session = Session::create(scene.value(), "pin");
  REQUIRE(session.ok());
  DeviceSample sample;
  sample.X_WD.p = Eigen::Vector3d(60, 0, 10);
  sample.engaged = true;
  REQUIRE(session.value().step(sample).ok());
  CHECK_THAT(session.value().switch_tool("ball").message, Catch::Contains("stroke is in progress"));
  sample.engaged = false;
  sample.tick = 1;
  REQUIRE(session.value().step(sample).ok());
  CHECK_THAT(session.value().switch_tool("chisel").message,
             Catch::Contains("\"chisel\" is not in the scene's tools"));
  CHECK(session.value().tool().name == "pin");
  CHECK(session.value().switch_tool("ball").ok());
  CHECK(session.value().tool().name == "ball");
}

TEST_CASE("a tool taken before the first tick: recorded.csv and the viewer's replay agree",
          "[run]") {
  fs::create_directories(kWork);
  const fs::path script = kWork / "first.csv";
  std::ofstream(script, std::ios::binary) << "# argil.script version 1\n"
                                             "# tool: pin\n"
                                             "t,x,y,z,qw,qx,qy,qz,event\n"
                                             "0,60,0,10,1,0,0,0,tool:ball\n"
                                             "0.04,60,0,1,1,0,0,0,engage\n"
                                             "0.1,60,10,-4,1,0,0,0,\n"
                                             "0.17,60,20,5,1,0,0,0,release\n"
                                             "0.2,60,20,10,1,0,0,0,\n";
  const fs::path out = kWork / "first";
  run_ok(options_for(script, out));
  run_ok(options_for(out / "recorded.csv", kWork / "first-replayed"));
  CHECK(same_bits(poles_of(out / "plate.json"), poles_of(kWork / "first-replayed" / "plate.json")));
  const Result<SessionReplay> replay = replay_session({.folder = out});
  INFO(replay.status().message);
  REQUIRE(replay.ok());
  CHECK(replay.value().tool_index.front() == 1);
}

TEST_CASE("the viewer's replay of a run with a tool switch reaches its surfaces and tools",
          "[run]") {
  const fs::path out = kWork / "viewed";
  RunOptions options = options_for(script_with("viewed", "0.2,100,0,10,1,0,0,0,tool:ball\n"), out);
  run_ok(options);
  const Result<SessionReplay> replay = replay_session({.folder = out});
  INFO(replay.status().message);
  REQUIRE(replay.ok());
  CHECK(same_bits(replay.value().frames.back().models[0].faces[0].surface.control_points,
                  poles_of(out / "plate.json")));
  REQUIRE_FALSE(replay.value().tool_index.empty());
  CHECK(replay.value().tool_index.front() == 0);
  CHECK(replay.value().tool_index.back() == 1);
}

}  // namespace argil::sculpt

namespace argil::sculpt {
namespace {

/// A session on the two-tool scene holding the pin, refined for both tools
/// along two presses (at x = 60 and x = 100).
Session two_tool_session() {
  const Result<Scene> scene = read_scene(kScene);
  REQUIRE(scene.ok());
  const std::vector<std::vector<Eigen::Vector3d>> paths = {
      {{60, 0, 1}, {60, 10, -4}, {60, 20, 5}}, {{100, 0, 1}, {100, 10, -4}, {100, 20, 5}}};
  Result<Session> s = Session::create(scene.value(), "pin", paths, {"ball"});
  REQUIRE(s.ok());
  return std::move(s).value();
}

/// Steps free moves above x, then a press through (x, 10, -4), released, then
/// (`trail`) free moves away.
void press(Session& s, double x, long long& tick, bool trail = true) {
  const auto step = [&](const Eigen::Vector3d& p, bool engaged) {
    DeviceSample d;
    d.tick = tick;
    d.t = static_cast<double>(tick) / 1000.0;
    d.X_WD.p = p;
    d.engaged = engaged;
    ++tick;
    REQUIRE(s.step(d).ok());
  };
  for (int k = 0; k < 20; ++k) step({x, 0, 10 - 0.45 * k}, false);
  for (int k = 0; k <= 60; ++k) step({x, k / 3.0, 1 - 5 * std::sin(M_PI * k / 60.0)}, true);
  step({x, 20, 5}, false);  // the release
  for (int k = 1; trail && k < 20; ++k) step({x, 20, 5 + 0.25 * k}, false);
}

}  // namespace

TEST_CASE(
    "undo keeps the tool in hand; redo makes the stroke with its own tool, then gives it back",
    "[run]") {
  long long t1 = 0, t2 = 0;
  // A: a pin press, the ball taken, the press undone, a press at 100.
  Session a = two_tool_session();
  press(a, 60, t1);
  REQUIRE(a.switch_tool("ball").ok());
  REQUIRE(a.undo().ok());
  CHECK(a.tool().name == "ball");
  press(a, 100, t1, false);
  // B: the same free moves (A's history after its undo), the ball, a press at 100.
  Session b = two_tool_session();
  long long free_ticks = 0;
  for (int k = 0; k < 20; ++k) {
    DeviceSample d;
    d.tick = free_ticks++;
    d.X_WD.p = Eigen::Vector3d(60, 0, 10 - 0.45 * k);
    REQUIRE(b.step(d).ok());
  }
  REQUIRE(b.switch_tool("ball").ok());
  press(b, 100, t2, false);
  CHECK(a.state_hash() == b.state_hash());

  // Redo after taking another tool: the stroke comes back as the ball made it,
  // and the hand keeps the pin taken since.
  REQUIRE(a.undo().ok());
  REQUIRE(a.switch_tool("pin").ok());
  REQUIRE(a.redo().ok());
  CHECK(a.tool().name == "pin");
  CHECK(a.current_faces(0).faces[0].surface.control_points ==
        b.current_faces(0).faces[0].surface.control_points);
}

TEST_CASE("two undos and two redos with free moves between the strokes restore the state exactly",
          "[run]") {
  long long tick = 0;
  Session s = two_tool_session();
  press(s, 60, tick);
  REQUIRE(s.switch_tool("ball").ok());
  press(s, 100, tick, false);
  const std::uint64_t state = s.state_hash();
  REQUIRE(s.undo().ok());
  REQUIRE(s.undo().ok());
  CHECK(s.tool().name == "ball");
  REQUIRE(s.switch_tool("pin").ok());
  REQUIRE(s.redo().ok());
  REQUIRE(s.redo().ok());
  CHECK(s.tool().name == "pin");
  REQUIRE(s.switch_tool("ball").ok());
  CHECK(s.state_hash() == state);
}

}  // namespace argil::sculpt
