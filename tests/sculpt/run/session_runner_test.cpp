// The session runner as a library user calls it: a run stopped part way (by its
// progress callback, or with its journal torn afterwards) resumes to control
// points bit-identical to an uninterrupted run, and each way a run can start
// from its folder's journal is decided, and reported, by code.
#include <catch2/catch.hpp>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

#include "argil/io/files/model_files.hpp"
#include "argil/sculpt/run/session_runner.hpp"

namespace argil::sculpt {
namespace {

namespace fs = std::filesystem;

const fs::path kWork = fs::path(ARGIL_BINARY_DIR) / "runner-test";
const fs::path kScene = fs::path(ARGIL_SOURCE_DIR) / "tests/data/sculpt/good.json";
/// Three presses of the pin into the plate, 0.2 s each (571 ticks at 1 kHz).
const fs::path kThreePresses = fs::path(ARGIL_SOURCE_DIR) / "tests/data/sculpt/three_presses.csv";

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Options writing only what the comparisons need; stops once `stop_after`
/// strokes are journalled (0: never).
RunOptions options_for(const fs::path& out, bool fresh, int stop_after = 0) {
  fs::create_directories(kWork);
  RunOptions o{.scene = kScene, .script = kThreePresses, .out = out, .fresh = fresh};
  o.outputs = OutputOptions{.step = false,
                            .iges = false,
                            .json = true,
                            .forces = true,
                            .contacts = false,
                            .timing = false,
                            .pictures = false};
  if (stop_after > 0) {
    o.on_progress = [stop_after](const RunProgress& p) {
      return p.strokes >= stop_after ? RunControl::stop : RunControl::proceed;
    };
  }
  return o;
}

RunReport run_ok(const RunOptions& options) {
  Result<RunReport> report = run_session(options);
  INFO(report.status().message);
  REQUIRE(report.ok());
  return std::move(report).value();
}

/// Control points and forces.csv of `out` equal those of an uninterrupted run
/// of the same inputs to the bit.
void check_same_as_whole(const fs::path& out) {
  const fs::path whole = out.string() + "-whole";
  fs::remove_all(whole);
  const Result<RunReport> run = run_session(options_for(whole, true));
  REQUIRE(run.ok());
  const Result<io::Model> a = io::read_model(out / "plate.json");
  const Result<io::Model> b = io::read_model(whole / "plate.json");
  REQUIRE(a.ok());
  REQUIRE(b.ok());
  const ControlNet& pa = a.value().faces[0].surface.control_points;
  const ControlNet& pb = b.value().faces[0].surface.control_points;
  REQUIRE(pa.size() == pb.size());
  CHECK(std::memcmp(pa.data(), pb.data(), sizeof(double) * static_cast<std::size_t>(pa.size())) ==
        0);
  CHECK(read_text(out / "forces.csv") == read_text(whole / "forces.csv"));
}

/// A run into `name` stopped after `strokes` journalled strokes.
fs::path stopped_run(const std::string& name, int strokes) {
  const fs::path out = kWork / name;
  fs::remove_all(out);
  const RunReport r = run_ok(options_for(out, true, strokes));
  REQUIRE(r.stopped);
  REQUIRE(r.strokes == strokes);
  REQUIRE(r.files.empty());
  REQUIRE_FALSE(fs::exists(out / "plate.json"));
  return out;
}

TEST_CASE("a run stopped by its progress callback resumes to bit-identical control points",
          "[run]") {
  const fs::path out = stopped_run("stopped", 2);
  const RunReport r = run_ok(options_for(out, false));
  CHECK(r.start == RunStart::resumed);
  CHECK(r.strokes_resumed == 2);
  CHECK(r.strokes == 3);
  CHECK(r.ticks_replayed > 0);
  CHECK(r.ticks_replayed + r.ticks_run == r.ticks);
  CHECK(r.wall_timing.ticks == r.ticks_run);
  CHECK(r.warnings.empty());
  REQUIRE_FALSE(r.files.empty());
  CHECK(r.files.back() == out / "session.journal");
  check_same_as_whole(out);
}

TEST_CASE("a journal torn in its last record resumes without it to bit-identical control points",
          "[run]") {
  const fs::path out = stopped_run("torn-record", 2);
  const std::string text = read_text(out / "session.journal");
  const std::size_t last_start = text.rfind('\n', text.size() - 2) + 1;
  std::ofstream(out / "session.journal", std::ios::binary | std::ios::trunc)
      << text.substr(0, last_start + (text.size() - last_start) / 2);
  const RunReport r = run_ok(options_for(out, false));
  CHECK(r.start == RunStart::resumed);
  CHECK(r.strokes_resumed == 1);
  CHECK(r.warnings.size() == 1);
  check_same_as_whole(out);
}

TEST_CASE("a journal with a torn header starts afresh with code torn_header", "[run]") {
  const fs::path out = kWork / "torn-header";
  fs::remove_all(out);
  fs::create_directories(out);
  std::ofstream(out / "session.journal", std::ios::binary) << "argil.journal 1 scene=00";
  const RunReport r = run_ok(options_for(out, false));
  CHECK(r.start == RunStart::torn_header);
  CHECK(r.ticks_replayed == 0);
  check_same_as_whole(out);
}

TEST_CASE("a finished journal starts afresh with code previous_finished", "[run]") {
  const fs::path out = kWork / "finished";
  fs::remove_all(out);
  CHECK(run_ok(options_for(out, false)).start == RunStart::no_journal);
  const RunReport again = run_ok(options_for(out, false));
  CHECK(again.start == RunStart::previous_finished);
  CHECK(again.ticks_run == again.ticks);
  CHECK(run_ok(options_for(out, true)).start == RunStart::fresh_requested);
  check_same_as_whole(out);
}

TEST_CASE("an unfinished journal of other inputs is refused with failed_precondition and kept",
          "[run]") {
  const fs::path out = stopped_run("other-inputs", 1);
  const std::string journal = read_text(out / "session.journal");
  RunOptions other = options_for(out, false);
  other.tolerance = 0.07;  // good.json has 0.05: the scene hash differs
  const Result<RunReport> refused = run_session(other);
  REQUIRE_FALSE(refused.ok());
  CHECK(refused.status().code == StatusCode::failed_precondition);
  CHECK(read_text(out / "session.journal") == journal);

  // The decision itself, on a header differing in the scene hash only.
  const JournalRead read = read_journal(out / "session.journal");
  REQUIRE(read.ok());
  JournalHeader changed = read.contents.header;
  CHECK(plan_resume(out / "session.journal", changed, false).value().start == RunStart::resumed);
  changed.scene_hash ^= 1;
  const Result<ResumePlan> plan = plan_resume(out / "session.journal", changed, false);
  REQUIRE_FALSE(plan.ok());
  CHECK(plan.status().code == StatusCode::failed_precondition);
  CHECK(plan_resume(out / "session.journal", changed, true).value().start ==
        RunStart::fresh_requested);
  CHECK(plan_resume(out / "no-such.journal", changed, false).value().start == RunStart::no_journal);
}

TEST_CASE("a journal damaged before intact records is refused with failed_precondition", "[run]") {
  const fs::path out = stopped_run("damaged", 2);
  std::string text = read_text(out / "session.journal");
  const std::size_t second_line = text.find('\n') + 1;
  text[second_line + 10] = text[second_line + 10] == '1' ? '2' : '1';
  std::ofstream(out / "session.journal", std::ios::binary | std::ios::trunc) << text;
  CHECK(read_journal(out / "session.journal").fault == JournalFault::damaged_record);
  const Result<RunReport> refused = run_session(options_for(out, false));
  REQUIRE_FALSE(refused.ok());
  CHECK(refused.status().code == StatusCode::failed_precondition);
}

TEST_CASE("a bad tolerance option is invalid_argument and writes nothing", "[run]") {
  const fs::path out = kWork / "bad-tolerance";
  fs::remove_all(out);
  for (const double bad : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN()}) {
    RunOptions o = options_for(out, true);
    o.tolerance = bad;
    const Result<RunReport> r = run_session(o);
    REQUIRE_FALSE(r.ok());
    CHECK(r.status().code == StatusCode::invalid_argument);
    CHECK_FALSE(fs::exists(out));
  }
}

TEST_CASE("a face STEP and IGES cannot take fails those two exports by name, the rest is written",
          "[run][export]") {
  // bad_export.json: the plate pressed three times, and a rigid face whose trim
  // loop crosses itself (a bow tie), which no valid CAD face can carry.
  const fs::path out = kWork / "bad-export";
  fs::remove_all(out);
  const RunOptions options{
      .scene = fs::path(ARGIL_SOURCE_DIR) / "tests/data/sculpt/bad_export.json",
      .out = out,
      .fresh = true};
  const RunReport r = run_ok(options);
  CHECK(r.strokes == 3);
  REQUIRE(r.failed_outputs.size() == 2);
  for (const auto& [failed, name] : {std::pair{r.failed_outputs[0], "bow_tie.step"},
                                     std::pair{r.failed_outputs[1], "bow_tie.iges"}}) {
    CHECK(failed.file == out / name);
    CHECK(failed.status.code == StatusCode::invalid_surface);
    CHECK_THAT(failed.status.message, Catch::StartsWith((out / name).string() + ": 1 of 1 faces"));
    CHECK_THAT(failed.status.message,
               Catch::Contains("face 0 (\"bow tie\") fails BRepCheck_Analyzer"));
    CHECK_THAT(failed.status.message,
               Catch::Contains("loop 0 (wire): BRepCheck_SelfIntersectingWire"));
    CHECK_FALSE(fs::exists(out / name));
  }
  const std::vector<fs::path> expected = {
      out / "plate.step",     out / "plate.iges",   out / "plate.json",  out / "bow_tie.json",
      out / "forces.csv",     out / "contacts.csv", out / "timing.json", out / "recorded.csv",
      out / "summary.json",   out / "before.png",   out / "after.png",   out / "force.png",
      out / "session.journal"};
  CHECK(r.files == expected);
  for (const fs::path& file : expected) {
    INFO(file);
    CHECK(fs::file_size(file) > 0);
  }
  // The sculpted plate is in the STEP file as in the JSON one, and the journal is
  // finished: the next run starts afresh.
  const Result<io::Model> step = io::read_model(out / "plate.step");
  const Result<io::Model> json = io::read_model(out / "plate.json");
  REQUIRE(step.ok());
  REQUIRE(json.ok());
  CHECK(step.value().faces[0].surface.control_points ==
        json.value().faces[0].surface.control_points);
  RunOptions again = options;
  again.fresh = false;
  again.outputs = OutputOptions{.step = false,
                                .iges = false,
                                .json = true,
                                .forces = false,
                                .contacts = false,
                                .timing = false,
                                .pictures = false};
  const RunReport second = run_ok(again);
  CHECK(second.start == RunStart::previous_finished);
  CHECK(second.failed_outputs.empty());
}

}  // namespace
}  // namespace argil::sculpt
