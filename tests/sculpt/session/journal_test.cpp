// The journal: records read back exactly, a torn last record is dropped, damage
// before intact records is an error; and `argil sculpt` killed with SIGKILL in
// the middle of a run resumes from its journal to bit-identical results.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <thread>

#include "argil/io/files/model_files.hpp"
#include "argil/sculpt/detail/fnv_hash.hpp"
#include "argil/sculpt/script/script.hpp"
#include "argil/sculpt/session/journal.hpp"

namespace argil::sculpt {
namespace {

const std::filesystem::path kWork = std::filesystem::path(ARGIL_BINARY_DIR) / "journal-test";

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<DeviceSample> samples(long long first, int count, bool engaged) {
  std::vector<DeviceSample> out;
  for (int k = 0; k < count; ++k) {
    DeviceSample s;
    s.tick = first + k;
    s.t = static_cast<double>(s.tick) / 1000.0;
    s.X_WD.p = Eigen::Vector3d(0.1 * k, -1.0 / 3.0, 1e-300 * k);
    s.X_WD.R = Eigen::Quaterniond(Eigen::AngleAxisd(0.01 * k, Eigen::Vector3d::UnitY()));
    s.engaged = engaged;
    out.push_back(s);
  }
  return out;
}

bool same_samples(const std::vector<DeviceSample>& a, const std::vector<DeviceSample>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t k = 0; k < a.size(); ++k) {
    if (a[k].tick != b[k].tick || a[k].engaged != b[k].engaged ||
        std::memcmp(&a[k].t, &b[k].t, sizeof(double)) != 0 ||
        std::memcmp(a[k].X_WD.p.data(), b[k].X_WD.p.data(), 3 * sizeof(double)) != 0 ||
        std::memcmp(a[k].X_WD.R.coeffs().data(), b[k].X_WD.R.coeffs().data(), 4 * sizeof(double)) !=
            0) {
      return false;
    }
  }
  return true;
}

TEST_CASE("journal records read back exactly and a torn last record is dropped", "[journal]") {
  std::filesystem::create_directories(kWork);
  const std::filesystem::path path = kWork / "unit.journal";
  const JournalHeader header{0x1234, 0xabcdef, 1000.0};
  JournalRecord a, b, undo;
  a.samples = samples(0, 30, true);
  a.state_hash = 42;
  b.samples = samples(30, 7, false);
  b.state_hash = 0xffffffffffffffffULL;
  undo.kind = JournalRecord::Kind::undo;
  undo.state_hash = 7;
  {
    Result<JournalWriter> w = JournalWriter::create(path, header);
    REQUIRE(w.ok());
    REQUIRE(w.value().append(a).ok());
    REQUIRE(w.value().append(undo).ok());
    REQUIRE(w.value().append(b).ok());
  }
  const JournalRead read = read_journal(path);
  INFO(read.status.message);
  REQUIRE(read.ok());
  CHECK(read.contents.header.scene_hash == 0x1234);
  CHECK(read.contents.header.script_hash == 0xabcdef);
  CHECK(read.contents.header.haptic_rate == 1000.0);
  REQUIRE(read.contents.records.size() == 3);
  CHECK(same_samples(read.contents.records[0].samples, a.samples));
  CHECK(read.contents.records[0].state_hash == 42);
  CHECK(read.contents.records[1].kind == JournalRecord::Kind::undo);
  CHECK(same_samples(read.contents.records[2].samples, b.samples));
  CHECK(read.contents.records[2].state_hash == b.state_hash);
  CHECK_FALSE(read.contents.finished);
  CHECK_FALSE(read.contents.dropped_torn_record);

  // A crash in the middle of writing the last record: every cut point of it.
  const std::string text = read_text(path);
  const std::size_t last_start = text.rfind('\n', text.size() - 2) + 1;
  for (std::size_t cut = last_start + 1; cut < text.size(); cut += 97) {
    const std::filesystem::path torn = kWork / "torn.journal";
    std::ofstream(torn, std::ios::binary) << text.substr(0, cut);
    const JournalRead r = read_journal(torn);
    REQUIRE(r.ok());
    CHECK(r.contents.records.size() == 2);
    CHECK(r.contents.dropped_torn_record);
    CHECK(r.contents.valid_bytes == last_start);
    // Appending after a torn tail cuts it off first.
    {
      Result<JournalWriter> w = JournalWriter::append_to(torn, r.contents);
      REQUIRE(w.ok());
      REQUIRE(w.value().finish().ok());
    }
    const JournalRead again = read_journal(torn);
    REQUIRE(again.ok());
    CHECK(again.contents.records.size() == 2);
    CHECK(again.contents.finished);
  }

  // A flipped byte in an earlier record is corruption, not a torn tail.
  std::string damaged = text;
  damaged[last_start / 2] = damaged[last_start / 2] == '1' ? '2' : '1';
  std::ofstream(kWork / "damaged.journal", std::ios::binary) << damaged;
  const JournalRead bad = read_journal(kWork / "damaged.journal");
  REQUIRE_FALSE(bad.ok());
  CHECK(bad.fault == JournalFault::damaged_record);
  CHECK(bad.status.message.find("damaged record") != std::string::npos);
}

/// A journal line as the writer makes it: the body and its FNV-1a check.
std::string checked_line(const std::string& body) {
  char check[20];
  std::snprintf(check, sizeof check, "%016" PRIx64, fnv1a64(body));
  return body + " check=" + check + "\n";
}

TEST_CASE("each journal that cannot be read reports why with its fault code", "[journal]") {
  std::filesystem::create_directories(kWork);
  const std::filesystem::path path = kWork / "fault.journal";
  const std::string header =
      checked_line("argil.journal 1 scene=0000000000001234 script=0000000000abcdef rate=0x1.f4p+9");
  const std::string record = checked_line("stroke 0 state=000000000000002a");
  const struct {
    std::string text;
    JournalFault fault;
  } cases[] = {
      {"", JournalFault::torn_header},
      {header.substr(0, header.size() / 2), JournalFault::torn_header},
      {checked_line("argil.journal 2 scene=0 script=0 rate=1") + record,
       JournalFault::not_a_journal},
      {header + checked_line("stroke two state=000000000000002a") + record,
       JournalFault::malformed_record},
      {header + checked_line("end") + record, JournalFault::record_after_end},
      {header + record.substr(0, 8) + "x" + record.substr(9) + record,
       JournalFault::damaged_record},
  };
  // The well-formed journal the cases are cut from reads back.
  std::ofstream(path, std::ios::binary | std::ios::trunc) << header << record << record;
  REQUIRE(read_journal(path).ok());
  CHECK(read_journal(path).contents.records.size() == 2);
  for (const auto& c : cases) {
    std::ofstream(path, std::ios::binary | std::ios::trunc) << c.text;
    const JournalRead read = read_journal(path);
    INFO(to_string(c.fault) << ": " << read.status.message);
    CHECK(read.fault == c.fault);
    CHECK(read.status.code == StatusCode::parse_error);
  }
  const JournalRead missing = read_journal(kWork / "no-such.journal");
  CHECK(missing.fault == JournalFault::unreadable);
  CHECK(missing.status.code == StatusCode::io_error);
}

/// Runs argil with `args`; stdout and stderr go to `log`. Returns the pid.
pid_t spawn(const std::vector<std::string>& args, const std::filesystem::path& log) {
  const pid_t pid = fork();
  if (pid == 0) {
    FILE* out = std::fopen(log.c_str(), "w");
    if (out != nullptr) {
      dup2(fileno(out), STDOUT_FILENO);
      dup2(fileno(out), STDERR_FILENO);
    }
    std::vector<char*> argv;
    std::string program = ARGIL_PROGRAM;
    argv.push_back(program.data());
    std::vector<std::string> copy = args;
    for (std::string& a : copy) argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(program.c_str(), argv.data());
    _exit(127);
  }
  return pid;
}

int wait_exit(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
}

int count_strokes(const std::filesystem::path& journal) {
  std::ifstream in(journal);
  std::string line;
  int strokes = 0;
  while (std::getline(in, line)) strokes += line.rfind("stroke ", 0) == 0;
  return strokes;
}

/// Four presses on the groove plate, 0.3 s each.
void write_four_presses(const std::filesystem::path& path) {
  Script s;
  s.tool = "pin";
  double t = 0.0;
  for (const double x : {50.0, 80.0, 120.0, 150.0}) {
    Keyframe above, engage, down, up;
    above.t = t;
    above.X_WD.p = {x, 0, 10};
    engage.t = t + 0.05;
    engage.X_WD.p = {x, 0, 1};
    engage.event = ScriptEvent::engage;
    down.t = t + 0.15;
    down.X_WD.p = {x, 10, -4};
    up.t = t + 0.25;
    up.X_WD.p = {x, 20, 5};
    up.event = ScriptEvent::release;
    s.keyframes.insert(s.keyframes.end(), {above, engage, down, up});
    t += 0.3;
  }
  REQUIRE(write_script(s, path).ok());
}

TEST_CASE("argil sculpt killed with SIGKILL resumes from its journal to bit-identical results",
          "[journal][kill]") {
  std::filesystem::remove_all(kWork / "killed");
  std::filesystem::remove_all(kWork / "whole");
  std::filesystem::create_directories(kWork);
  const std::string scene = std::string(ARGIL_SOURCE_DIR) + "/examples/groove/scene.json";
  const std::filesystem::path script = kWork / "four_presses.csv";
  write_four_presses(script);

  // A paced run (like a live device), killed once at least one stroke is
  // journalled and before the last one is.
  const pid_t victim = spawn({"sculpt", scene, "--script", script.string(), "--out",
                              (kWork / "killed").string(), "--fresh", "--realtime"},
                             kWork / "killed.log");
  const std::filesystem::path journal = kWork / "killed" / "session.journal";
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (count_strokes(journal) < 2 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  REQUIRE(kill(victim, SIGKILL) == 0);
  CHECK(wait_exit(victim) == -SIGKILL);
  const int journalled = count_strokes(journal);
  INFO("strokes journalled when killed: " << journalled);
  REQUIRE(journalled >= 2);
  REQUIRE(journalled < 4);
  // Killed mid-run: no surface was exported yet.
  CHECK_FALSE(std::filesystem::exists(kWork / "killed" / "plate.json"));

  // Resume (same inputs, no --fresh) and an uninterrupted run.
  CHECK(wait_exit(spawn(
            {"sculpt", scene, "--script", script.string(), "--out", (kWork / "killed").string()},
            kWork / "resumed.log")) == 0);
  CHECK(read_text(kWork / "resumed.log").find("resumed from") != std::string::npos);
  CHECK(wait_exit(spawn({"sculpt", scene, "--script", script.string(), "--out",
                         (kWork / "whole").string(), "--fresh"},
                        kWork / "whole.log")) == 0);

  const Result<io::Model> resumed = io::read_model(kWork / "killed" / "plate.json");
  const Result<io::Model> whole = io::read_model(kWork / "whole" / "plate.json");
  REQUIRE(resumed.ok());
  REQUIRE(whole.ok());
  const ControlNet& a = resumed.value().faces[0].surface.control_points;
  const ControlNet& b = whole.value().faces[0].surface.control_points;
  REQUIRE(a.size() == b.size());
  CHECK(std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0);
  // The logs of the resumed run cover every tick and match too.
  CHECK(read_text(kWork / "killed" / "forces.csv") == read_text(kWork / "whole" / "forces.csv"));
  CHECK(count_strokes(kWork / "killed" / "session.journal") == 4);
}

}  // namespace
}  // namespace argil::sculpt
