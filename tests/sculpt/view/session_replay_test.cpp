// The viewer's replay of a finished run and the page made from it: the replay
// reaches the run's surfaces to the bit, checks itself against the journal,
// and refuses folders, scenes and recordings that are not the run's; the
// page's frames are the surfaces evaluated at the mesh's (u, v).
#include <catch2/catch.hpp>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "../run/run_checks.hpp"
#include "argil/core/geometry/evaluate.hpp"
#include "argil/io/files/model_files.hpp"
#include "argil/sculpt/run/session_runner.hpp"
#include "argil/sculpt/view/session_replay.hpp"
#include "argil/sculpt/view/view_page.hpp"

namespace argil::sculpt {
namespace {

namespace fs = std::filesystem;
using test::same_bits;

const fs::path kWork = fs::path(ARGIL_BINARY_DIR) / "session-replay-test";
const fs::path kScene = fs::path(ARGIL_SOURCE_DIR) / "tests/data/sculpt/good.json";

/// Two presses of the pin into the plate, the second taken back by an undo.
fs::path write_script(const std::string& name) {
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
         "0.4,100,20,10,1,0,0,0,undo\n"
         "0.45,100,20,12,1,0,0,0,\n";
  return path;
}

/// The run, in a folder of its own for each test case: CTest runs the cases
/// as separate processes side by side.
fs::path finished_run(const std::string& name) {
  const fs::path folder = kWork / name;
  test::run_ok(test::json_run(kScene, write_script(name), folder));
  return folder;
}

std::vector<std::uint8_t> unbase64(const std::string& text) {
  std::vector<std::uint8_t> out;
  std::uint32_t bits = 0;
  int count = 0;
  for (const char c : text) {
    const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    const char* at = std::strchr(digits, c);
    if (c == '=' || at == nullptr) break;
    bits = (bits << 6) | static_cast<std::uint32_t>(at - digits);
    count += 6;
    if (count >= 8) {
      count -= 8;
      out.push_back(static_cast<std::uint8_t>((bits >> count) & 0xff));
    }
  }
  return out;
}

template <class T>
std::vector<T> array_of(const nlohmann::json& base64) {
  const std::vector<std::uint8_t> bytes = unbase64(base64.get<std::string>());
  std::vector<T> out(bytes.size() / sizeof(T));
  std::memcpy(out.data(), bytes.data(), out.size() * sizeof(T));
  return out;
}

/// The JSON a page embeds.
nlohmann::json page_json(const std::string& page) {
  const std::string open = "<script id=\"argil-data\" type=\"application/json\">";
  const std::size_t begin = page.find(open);
  REQUIRE(begin != std::string::npos);
  const std::size_t end = page.find("</script>", begin);
  std::string text = page.substr(begin + open.size(), end - begin - open.size());
  CHECK(text.find('<') == std::string::npos);  // written \u003c: JSON reads it back
  return nlohmann::json::parse(text);
}

}  // namespace

TEST_CASE("a replay reaches the run's surfaces to the bit, with frames at strokes and undo",
          "[view]") {
  const fs::path run = finished_run("frames");
  const Result<SessionReplay> replay = replay_session({.folder = run, .every = 50});
  INFO(replay.status().message);
  REQUIRE(replay.ok());
  const SessionReplay& r = replay.value();
  const Result<io::Model> after = io::read_model(run / "plate.json");
  REQUIRE(after.ok());
  REQUIRE_FALSE(r.frames.empty());
  CHECK(same_bits(r.frames.back().models[0].faces[0].surface.control_points,
                  after.value().faces[0].surface.control_points));
  std::vector<std::string> kinds;
  for (const ReplayFrame& f : r.frames)
    if (f.kind != "tick") kinds.push_back(f.kind);
  CHECK(kinds == std::vector<std::string>{"stroke end", "stroke end", "undo", "end"});
  // The undo's frame is the first stroke's surfaces again.
  const auto frame_of = [&](const std::string& kind, int nth) {
    for (const ReplayFrame& f : r.frames)
      if (f.kind == kind && nth-- == 0) return &f;
    return static_cast<const ReplayFrame*>(nullptr);
  };
  REQUIRE(frame_of("undo", 0) != nullptr);
  CHECK(same_bits(frame_of("undo", 0)->models[0].faces[0].surface.control_points,
                  frame_of("stroke end", 0)->models[0].faces[0].surface.control_points));
  CHECK_FALSE(same_bits(frame_of("stroke end", 1)->models[0].faces[0].surface.control_points,
                        frame_of("stroke end", 0)->models[0].faces[0].surface.control_points));
  // Every 50th tick is a frame, and every tick is logged.
  CHECK(std::count_if(r.frames.begin(), r.frames.end(), [](const ReplayFrame& f) {
          return f.kind == "tick";
        }) == static_cast<long>(r.time.size() / 50));
  CHECK(r.device.size() == r.time.size());
  CHECK(r.force.size() == r.time.size());
  CHECK(r.engaged.size() == r.time.size());
}

TEST_CASE("the page's frames are the surfaces at the mesh's (u, v); it moved in where pressed",
          "[view]") {
  const Result<SessionReplay> replay = replay_session({.folder = finished_run("page")});
  REQUIRE(replay.ok());
  const Result<std::string> page = session_view_page(replay.value(), {.title = "plate"});
  INFO(page.status().message);
  REQUIRE(page.ok());
  const nlohmann::json data = page_json(page.value());
  CHECK(data["format"] == "argil.view");
  REQUIRE(data["faces"].size() == 1);
  REQUIRE(data["frames"].size() == replay.value().frames.size());
  const std::vector<double> uv = array_of<double>(data["faces"][0]["uv"]);
  const std::vector<float> before = array_of<float>(data["faces"][0]["positions"]);
  const std::vector<float> normals = array_of<float>(data["faces"][0]["normals"]);
  REQUIRE(before.size() == uv.size() / 2 * 3);
  // The last frame that lists the face holds the run's final surface.
  std::vector<float> last;
  std::size_t listed = 0;
  for (const nlohmann::json& frame : data["frames"]) {
    if (frame["faces"].contains("0")) {
      last = array_of<float>(frame["faces"]["0"]);
      ++listed;
    }
  }
  CHECK(listed >= 3);  // the first press, the second, and the undo
  REQUIRE(last.size() == before.size());
  const io::FaceRecord& end = replay.value().frames.back().models[0].faces[0];
  double worst = 0.0, deepest = 0.0;
  for (std::size_t k = 0; k < uv.size() / 2; ++k) {
    const Eigen::Vector3d p = evaluate(end.surface, uv[2 * k], uv[2 * k + 1]);
    Eigen::Vector3d shown, was, n;
    for (int c = 0; c < 3; ++c) {
      shown[c] = last[3 * k + static_cast<std::size_t>(c)];
      was[c] = before[3 * k + static_cast<std::size_t>(c)];
      n[c] = normals[3 * k + static_cast<std::size_t>(c)];
    }
    worst = std::max(worst, (shown - p).norm() / std::max(1.0, p.norm()));
    deepest = std::min(deepest, (shown - was).dot(n));
  }
  CHECK(worst < 1e-6);  // float32 rounding
  CHECK(deepest < -replay.value().scene.tolerance);
  CHECK(data["run"]["rate"] == replay.value().haptic_rate);
  REQUIRE(data["tools"].size() == 1);
  CHECK(data["tools"][0]["type"] == "point");
}

TEST_CASE("a run started with a relative scene path replays from another directory", "[view]") {
  // summary.json names the scene as given (relative to where the run
  // started) and by its absolute path, which `argil view` reads first.
  struct WorkingDirectory {  // restored however the case ends
    fs::path saved = fs::current_path();
    ~WorkingDirectory() { fs::current_path(saved); }
  } restore;
  const fs::path folder = kWork / "relative";
  const fs::path script = write_script("relative");
  fs::current_path(kScene.parent_path());
  test::run_ok(test::json_run(kScene.filename(), script, folder));
  // From here the name as given reaches nothing; then another scene of the
  // same name, which the replay must not take for the run's.
  for (const bool decoy : {false, true}) {
    CAPTURE(decoy);
    const fs::path elsewhere = kWork / (decoy ? "decoy" : "nothing");
    fs::create_directories(elsewhere);
    if (decoy)
      fs::copy_file(kScene.parent_path() / "summary_press.json", elsewhere / kScene.filename(),
                    fs::copy_options::overwrite_existing);
    fs::current_path(elsewhere);
    CHECK(fs::exists(kScene.filename()) == decoy);
    const Result<SessionReplay> replay = replay_session({.folder = folder});
    INFO(replay.status().message);
    CHECK(replay.ok());
  }
}

TEST_CASE("a replay refuses what is not the run: a folder, another scene, a changed recording",
          "[view]") {
  const fs::path run = finished_run("refusals");
  SECTION("a folder without a run names summary.json") {
    fs::create_directories(kWork / "empty");
    const Result<SessionReplay> r = replay_session({.folder = kWork / "empty"});
    REQUIRE_FALSE(r.ok());
    CHECK_THAT(r.status().message, Catch::Contains("summary.json") &&
                                       Catch::Contains("not the output folder of a finished run"));
  }
  SECTION("a scene other than the run's") {
    // The run's scene with its model named by absolute path: the same run,
    // but not the same bytes.
    std::ifstream in(kScene, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    std::string scene = text.str();
    const std::string relative = "../../../examples/groove/plate.json";
    REQUIRE(scene.find(relative) != std::string::npos);
    scene.replace(scene.find(relative), relative.size(),
                  (fs::path(ARGIL_SOURCE_DIR) / "examples/groove/plate.json").string());
    const fs::path other = kWork / "other_scene.json";
    std::ofstream(other, std::ios::binary) << scene;
    const Result<SessionReplay> r = replay_session({.folder = run, .scene = other});
    REQUIRE_FALSE(r.ok());
    CHECK(r.status().code == StatusCode::failed_precondition);
    CHECK_THAT(r.status().message,
               Catch::Contains("other_scene.json") && Catch::Contains("changed since the run"));
  }
  SECTION("a recording whose stroke was changed does not reach the journal's state") {
    const fs::path copy = kWork / "tampered";
    fs::remove_all(copy);
    fs::copy(run, copy);
    std::ifstream in(copy / "recorded.csv", std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    in.close();
    std::string csv = text.str();
    // Shift every sample of the first press 0.5 mm deeper.
    std::istringstream lines(csv);
    std::string out, line;
    while (std::getline(lines, line)) {
      std::vector<std::string> cells;
      std::stringstream cellstream(line);
      for (std::string cell; std::getline(cellstream, cell, ',');) cells.push_back(cell);
      if (cells.size() >= 4 && line[0] != '#' && line[0] != 't') {
        const double t = std::stod(cells[0]);
        if (t > 0.05 && t < 0.15) cells[3] = std::to_string(std::stod(cells[3]) - 0.5);
      }
      std::string joined;
      for (std::size_t i = 0; i < cells.size(); ++i) joined += (i ? "," : "") + cells[i];
      if (!line.empty() && line.back() == ',') joined += ",";
      out += joined + "\n";
    }
    std::ofstream(copy / "recorded.csv", std::ios::binary) << out;
    const Result<SessionReplay> r = replay_session({.folder = copy});
    REQUIRE_FALSE(r.ok());
    CHECK_THAT(r.status().message, Catch::Contains("recorded.csv") &&
                                       Catch::Contains("differ from the state session.journal"));
  }
}

}  // namespace argil::sculpt
