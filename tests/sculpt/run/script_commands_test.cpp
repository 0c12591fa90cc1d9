// Undo and redo as script events: run through the session runner, they take
// back and restore whole strokes exactly, resume from the journal to the same
// bits, replay from recorded.csv, and fail by keyframe when there is nothing
// to take back.
#include <catch2/catch.hpp>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>

#include "argil/io/files/model_files.hpp"
#include "argil/sculpt/run/session_runner.hpp"
#include "run_checks.hpp"

namespace argil::sculpt {
namespace {

namespace fs = std::filesystem;
using test::poles_of;
using test::run_ok;
using test::same_bits;

const fs::path kWork = fs::path(ARGIL_BINARY_DIR) / "script-commands-test";
const fs::path kScene = fs::path(ARGIL_SOURCE_DIR) / "tests/data/sculpt/good.json";
const fs::path kPlate = fs::path(ARGIL_SOURCE_DIR) / "examples/groove/plate.json";

/// Two presses of the pin into the plate (0.2 s each), then `tail` (CSV lines).
fs::path script_with(const std::string& name, const std::string& tail) {
  fs::create_directories(kWork);
  const fs::path path = kWork / (name + ".csv");
  std::ofstream out(path, std::ios::binary);
  out << "# argil.script version 1\n"
         "t,x,y,z,qw,qx,qy,qz,event\n"
         "0,60,0,10,1,0,0,0,\n"
         "0.04,60,0,1,1,0,0,0,engage\n"
         "0.1,60,10,-4,1,0,0,0,\n"
         "0.17,60,20,5,1,0,0,0,release\n"
         "0.2,100,0,10,1,0,0,0,\n"
         "0.24,100,0,1,1,0,0,0,engage\n"
         "0.3,100,10,-4,1,0,0,0,\n"
         "0.37,100,20,5,1,0,0,0,release\n"
      << tail;
  return path;
}

RunOptions options_for(const fs::path& script, const fs::path& out, bool fresh = true) {
  return test::json_run(kScene, script, out, fresh);
}

}  // namespace

TEST_CASE("undo events take strokes back to the bit, and redo restores them", "[run]") {
  const ControlNet original = poles_of(kPlate);
  const fs::path plain = kWork / "plain";
  run_ok(options_for(script_with("plain", "0.45,100,20,10,1,0,0,0,\n"), plain));
  const ControlNet pressed = poles_of(plain / "plate.json");
  REQUIRE_FALSE(same_bits(pressed, original));

  // Both presses taken back: the plate as read.
  const fs::path undone = kWork / "undone";
  const RunReport u =
      run_ok(options_for(script_with("undone",
                                     "0.4,100,20,10,1,0,0,0,undo\n0.42,100,20,10,1,0,0,0,undo\n"
                                     "0.45,100,20,10,1,0,0,0,\n"),
                         undone));
  CHECK(u.strokes == 2);
  CHECK(same_bits(poles_of(undone / "plate.json"), original));

  // Taken back and restored: the plain run's plate.
  const fs::path redone = kWork / "redone";
  const fs::path redone_script =
      script_with("redone",
                  "0.4,100,20,10,1,0,0,0,undo\n0.42,100,20,10,1,0,0,0,redo\n"
                  "0.45,100,20,10,1,0,0,0,\n");
  run_ok(options_for(redone_script, redone));
  CHECK(same_bits(poles_of(redone / "plate.json"), pressed));

  // recorded.csv carries the commands: replaying it gives the same plate.
  std::ifstream recorded(redone / "recorded.csv");
  const std::string text((std::istreambuf_iterator<char>(recorded)),
                         std::istreambuf_iterator<char>());
  CHECK(text.find(",undo\n") != std::string::npos);
  CHECK(text.find(",redo\n") != std::string::npos);
  const RunOptions replay = options_for(redone / "recorded.csv", kWork / "replayed");
  run_ok(replay);
  CHECK(same_bits(poles_of(kWork / "replayed" / "plate.json"), pressed));
}

TEST_CASE("a run with undo stopped part way resumes to the same bits", "[run]") {
  const fs::path script = script_with("resumed",
                                      "0.4,100,20,10,1,0,0,0,undo\n0.44,140,0,1,1,0,0,0,engage\n"
                                      "0.5,140,10,-4,1,0,0,0,\n0.57,140,20,5,1,0,0,0,release\n");
  const fs::path whole = kWork / "resumed-whole";
  run_ok(options_for(script, whole));
  const fs::path out = kWork / "resumed";
  fs::remove_all(out);
  RunOptions stopping = options_for(script, out);
  // Stop once the second stroke is journalled: the undo comes after the resume.
  stopping.on_progress = [](const RunProgress& p) {
    return p.strokes >= 2 ? RunControl::stop : RunControl::proceed;
  };
  REQUIRE(run_ok(stopping).stopped);
  const RunReport resumed = run_ok(options_for(script, out, false));
  CHECK(resumed.start == RunStart::resumed);
  CHECK(resumed.strokes == 3);
  CHECK(same_bits(poles_of(out / "plate.json"), poles_of(whole / "plate.json")));
  // And stopped after the undo (the third stroke started): resumes the same.
  const fs::path late = kWork / "resumed-late";
  fs::remove_all(late);
  RunOptions stopping_late = options_for(script, late);
  stopping_late.on_progress = [](const RunProgress& p) {
    return p.ticks_done >= 460 ? RunControl::stop : RunControl::proceed;
  };
  stopping_late.progress_every = 1;
  REQUIRE(run_ok(stopping_late).stopped);
  run_ok(options_for(script, late, false));
  CHECK(same_bits(poles_of(late / "plate.json"), poles_of(whole / "plate.json")));
}

TEST_CASE("undo with nothing to take back fails naming the keyframe; undo while engaged is refused",
          "[run]") {
  const fs::path out = kWork / "too-many";
  const Result<RunReport> r = run_session(
      options_for(script_with("too-many",
                              "0.4,100,20,10,1,0,0,0,undo\n0.41,100,20,10,1,0,0,0,undo\n"
                              "0.42,100,20,10,1,0,0,0,undo\n"),
                  out));
  REQUIRE_FALSE(r.ok());
  CHECK_THAT(r.status().message, Catch::Contains("script keyframe 10 (t = 0.42 s): undo:"));
  const Result<RunReport> engaged = run_session(options_for(
      script_with("engaged", "0.4,100,20,10,1,0,0,0,engage\n0.42,100,20,10,1,0,0,0,undo\n"),
      kWork / "engaged"));
  REQUIRE_FALSE(engaged.ok());
  CHECK_THAT(engaged.status().message, Catch::Contains("undo while engaged: release first"));
}

}  // namespace argil::sculpt
