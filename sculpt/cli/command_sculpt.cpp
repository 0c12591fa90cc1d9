// argil sculpt SCENE [--script S] [--out DIR] [--tolerance E] [--fresh] [--realtime]:
// runs a session from a scripted device and writes the sculpted surfaces, logs,
// timing and pictures. Resumes from DIR/session.journal after a crash.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "argil/io/base/atomic_write.hpp"
#include "argil/io/base/text_file.hpp"
#include "argil/io/files/model_files.hpp"
#include "argil/sculpt/output/session_pictures.hpp"
#include "argil/sculpt/output/tick_log.hpp"
#include "argil/sculpt/scene/scene.hpp"
#include "argil/sculpt/script/script.hpp"
#include "argil/sculpt/session/journal.hpp"
#include "argil/sculpt/session/session.hpp"
#include "commands.hpp"

namespace argil::cli {
namespace {

using namespace argil::sculpt;
using Clock = std::chrono::steady_clock;

constexpr const char* kJournalName = "session.journal";
constexpr const char* kRecordedScriptName = "recorded.csv";
// Longest run: about 2.8 hours at 1 kHz; samples and log rows are kept in memory.
constexpr double kMaxTicks = 1e7;

struct Options {
  std::filesystem::path scene, script, out;
  double tolerance = 0.0;  // 0: the scene's
  bool fresh = false;
  bool realtime = false;
};

// The run below names its inputs by this hash; the journal owns its definition.
std::uint64_t fnv1a64(std::string_view bytes) { return journal_input_hash(bytes); }

/// Checks the command line; returns -1 when the run should go ahead with `o`
/// filled in, else the exit status.
int parse(const std::vector<std::string>& args, Options& o) {
  const ParseResult parsed = parse_arguments(sculpt_command(), args);
  if (!parsed.arguments) return parsed.exit_status;
  const Arguments& a = *parsed.arguments;
  o.scene = a.operands[0];
  o.script = a.text("--script").value_or("");
  o.out = a.text("--out").value_or("");
  o.tolerance = a.number("--tolerance").value_or(0.0);
  o.fresh = a.flag("--fresh");
  o.realtime = a.flag("--realtime");
  return -1;
}

/// CPU time of the calling thread [s]: a tick's own cost, excluding preemption.
double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

int fail(const std::string& message) {
  std::fprintf(stderr, "argil sculpt: %s\n", message.c_str());
  return kExitFailure;
}

/// A one-line progress bar on stderr, drawn only on a terminal.
class ProgressBar {
 public:
  explicit ProgressBar(long long total) : total_(total), enabled_(isatty(STDERR_FILENO) == 1) {}
  void update(long long done, int strokes) {
    if (!enabled_) return;
    const Clock::time_point now = Clock::now();
    if (done < total_ && now - last_ < std::chrono::milliseconds(100)) return;
    last_ = now;
    const int width = 32;
    const double fraction =
        total_ > 0 ? static_cast<double>(done) / static_cast<double>(total_) : 1.0;
    const int filled = static_cast<int>(fraction * width);
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.resize(width, '.');
    std::fprintf(stderr, "\r[%s] %3d%%  tick %lld/%lld  strokes %d", bar.c_str(),
                 static_cast<int>(fraction * 100.0), done, total_, strokes);
    std::fflush(stderr);
  }
  void finish() {
    if (enabled_) std::fprintf(stderr, "\n");
  }

 private:
  long long total_;
  bool enabled_;
  Clock::time_point last_{};
};

}  // namespace

const CommandSpec& sculpt_command() {
  static const CommandSpec spec{
      .name = "sculpt",
      .operands = {"SCENE"},
      .summary = "run a sculpting session: a scene's tool driven by a script",
      .description =
          "Writes the sculpted surfaces (STEP, IGES, JSON), forces.csv, contacts.csv,\n"
          "timing.json, recorded.csv and pictures to DIR. An interrupted run resumes\n"
          "from DIR/session.journal.",
      .options = {{.name = "--script",
                   .argument = "S",
                   .kind = ValueKind::text,
                   .description = "the device script (.json or .csv)",
                   .default_text = "the scene's \"script\""},
                  {.name = "--out",
                   .argument = "DIR",
                   .kind = ValueKind::text,
                   .description = "the output folder",
                   .default_text = "out/<scene name>"},
                  {.name = "--tolerance",
                   .argument = "E",
                   .kind = ValueKind::number,
                   .description = "eps, the contact distance; overrides the scene's",
                   .range = kPositiveFinite,
                   .unit = "mm",
                   .default_text = "the scene's \"tolerance\""},
                  {.name = "--fresh",
                   .description = "ignore an unfinished journal in DIR instead of resuming from it",
                   .default_text = "off"},
                  {.name = "--realtime",
                   .description = "pace ticks at the haptic rate like a live device",
                   .default_text = "off"}},
  };
  return spec;
}

int run_sculpt(const std::vector<std::string>& args) {
  Options o;
  if (const int status = parse(args, o); status >= 0) return status;

  // ---- Inputs: everything is checked before anything is written. --------
  Result<Scene> scene_read = read_scene(o.scene);
  if (!scene_read.ok()) return fail(scene_read.status().message);
  Scene scene = std::move(scene_read).value();
  const Result<std::string> scene_read_bytes = argil::io::read_text_file(o.scene);
  if (!scene_read_bytes.ok()) return fail(scene_read_bytes.status().message);
  const std::string& scene_bytes = scene_read_bytes.value();
  if (o.tolerance > 0.0) scene.tolerance = o.tolerance;
  if (o.script.empty()) o.script = scene.script;
  if (o.script.empty()) {
    return fail(o.scene.string() + ": no script: pass --script or set \"script\" in the scene");
  }
  Result<Script> script_read = read_script(o.script);
  if (!script_read.ok()) return fail(script_read.status().message);
  const Script& script = script_read.value();
  if (scene.tool_index(script.tool) < 0) {
    return fail(o.script.string() + ": tool: \"" + script.tool + "\" is not a tool of " +
                o.scene.string());
  }
  // Every tick's sample and log row stay in memory until the end.
  const double ticks = script.keyframes.back().time * scene.haptic_rate;
  if (ticks > kMaxTicks) {
    char message[160];
    std::snprintf(
        message, sizeof message,
        ": keyframes[%zu].t: the script lasts %.17g s, %.3g ticks at %g Hz (at most %.0f)",
        script.keyframes.size() - 1, script.keyframes.back().time, ticks, scene.haptic_rate,
        kMaxTicks);
    return fail(o.script.string() + message);
  }
  const Result<std::string> script_read_bytes = argil::io::read_text_file(o.script);
  if (!script_read_bytes.ok()) return fail(script_read_bytes.status().message);
  const std::string& script_bytes = script_read_bytes.value();
  Result<Session> created = Session::create(scene, script.tool);
  if (!created.ok()) return fail(o.scene.string() + ": " + created.status().message);
  Session session = std::move(created).value();
  const ScriptSampler sampler(script, scene.haptic_rate);
  const std::string scene_name = o.scene.stem().string() == "scene"
                                     ? o.scene.parent_path().filename().string()
                                     : o.scene.stem().string();
  if (o.out.empty()) o.out = std::filesystem::path("out") / scene_name;
  std::vector<io::Model> before;
  for (int m = 0; m < static_cast<int>(session.models().size()); ++m) {
    before.push_back(session.current_model(m));
  }

  std::error_code ec;
  std::filesystem::create_directories(o.out, ec);
  if (ec) return fail(o.out.string() + ": cannot create the output folder: " + ec.message());

  // ---- Journal: resume an unfinished run with the same inputs. -----------
  JournalHeader header;
  char tolerance_text[40];
  std::snprintf(tolerance_text, sizeof tolerance_text, " tolerance=%a", scene.tolerance);
  header.scene_hash = fnv1a64(scene_bytes + tolerance_text);
  header.script_hash = fnv1a64(script_bytes);
  header.haptic_rate = scene.haptic_rate;
  const std::filesystem::path journal_path = o.out / kJournalName;
  std::optional<JournalContents> resume;
  if (!o.fresh && std::filesystem::exists(journal_path)) {
    Result<JournalContents> read = read_journal(journal_path);
    if (read.ok() && !read.value().finished) {
      const JournalHeader& h = read.value().header;
      if (h.scene_hash != header.scene_hash || h.script_hash != header.script_hash ||
          h.haptic_rate != header.haptic_rate) {
        return fail(journal_path.string() +
                    ": an unfinished run of another scene, script or tolerance; rerun with "
                    "--fresh to discard it");
      }
      resume = std::move(read).value();
    } else if (!read.ok() && read.status().message.find("torn header") == std::string::npos) {
      return fail(read.status().message + " (rerun with --fresh to discard the journal)");
    }
  }
  Result<JournalWriter> journal = resume ? JournalWriter::append_to(journal_path, *resume)
                                         : JournalWriter::create(journal_path, header);
  if (!journal.ok()) return fail(journal.status().message);

  // ---- The run. -----------------------------------------------------------
  TickLog log;
  std::vector<double> durations, cpu_durations;
  std::vector<DeviceSample> received;  // every sample, for recorded.csv and the path
  std::vector<DeviceSample> unjournalled;
  int strokes = 0;
  long long next_tick = 0;
  if (resume) {
    // Replay through the same steps; the state after each record must match.
    for (std::size_t r = 0; r < resume->records.size(); ++r) {
      const JournalRecord& record = resume->records[r];
      if (record.kind == JournalRecord::Kind::stroke) {
        for (const DeviceSample& s : record.samples) {
          if (s.tick != next_tick) {
            return fail(journal_path.string() + ": record " + std::to_string(r) +
                        " skips from tick " + std::to_string(next_tick) + " to " +
                        std::to_string(s.tick));
          }
          Result<TickReport> report = session.step(s);
          if (!report.ok()) return fail(report.status().message);
          log.add(report.value());
          received.push_back(s);
          ++next_tick;
        }
        ++strokes;
      } else {
        const Status done =
            record.kind == JournalRecord::Kind::undo ? session.undo() : session.redo();
        if (!done.ok()) return fail(journal_path.string() + ": " + done.message);
      }
      if (session.state_hash() != record.state_hash) {
        return fail(journal_path.string() + ": record " + std::to_string(r) +
                    " does not replay to the journalled state (inputs changed?); rerun with "
                    "--fresh");
      }
    }
    std::fprintf(stderr, "argil sculpt: resumed from %s: %zu records, %d strokes, ticks 0..%lld\n",
                 journal_path.c_str(), resume->records.size(), strokes, next_tick - 1);
  }

  ProgressBar progress(sampler.tick_count());
  const Clock::time_point run_start = Clock::now();
  for (long long k = next_tick; k < sampler.tick_count(); ++k) {
    const DeviceSample sample = sampler.sample(k);
    if (o.realtime) {
      std::this_thread::sleep_until(
          run_start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(
                          static_cast<double>(k - next_tick) / scene.haptic_rate)));
    }
    const double cpu0 = thread_cpu_seconds();
    const Clock::time_point t0 = Clock::now();
    Result<TickReport> report = session.step(sample);
    const Clock::time_point t1 = Clock::now();
    const double cpu1 = thread_cpu_seconds();
    if (!report.ok()) return fail(report.status().message);
    durations.push_back(std::chrono::duration<double>(t1 - t0).count());
    cpu_durations.push_back(cpu1 - cpu0);
    log.add(report.value());
    received.push_back(sample);
    unjournalled.push_back(sample);
    // A stroke is journalled when it finishes, and so is one the script ends in.
    if (report.value().stroke_finished || (k + 1 == sampler.tick_count() && sample.engaged)) {
      JournalRecord record;
      record.samples = std::move(unjournalled);
      unjournalled.clear();
      record.state_hash = session.state_hash();
      const Status appended = journal.value().append(record);
      if (!appended.ok()) return fail(appended.message);
      ++strokes;
    }
    progress.update(k + 1, strokes);
  }
  progress.finish();

  // ---- Outputs, each written atomically. ---------------------------------
  std::vector<std::string> written;
  auto write = [&](const std::filesystem::path& path, const Status& status) {
    if (status.ok()) written.push_back(path.string());
    return status;
  };
  std::vector<std::string> model_names;
  std::vector<io::Model> after;
  for (int m = 0; m < static_cast<int>(session.models().size()); ++m) {
    const LoadedModel& loaded = session.models()[static_cast<std::size_t>(m)];
    model_names.push_back(loaded.spec.name);
    after.push_back(session.current_model(m));
    const OutputSpec& out = scene.outputs;
    for (const auto& [wanted, extension] :
         {std::pair{out.step, ".step"}, std::pair{out.iges, ".iges"},
          std::pair{out.json, ".json"}}) {
      if (!wanted) continue;
      const std::filesystem::path path = o.out / (loaded.spec.name + extension);
      const Status status = write(path, io::write_model(after.back(), path));
      if (!status.ok()) return fail(status.message);
    }
  }
  if (scene.outputs.forces) {
    const Status s = write(o.out / "forces.csv",
                           io::write_bytes_atomically(o.out / "forces.csv", log.forces_csv()));
    if (!s.ok()) return fail(s.message);
  }
  if (scene.outputs.contacts) {
    const Status s =
        write(o.out / "contacts.csv",
              io::write_bytes_atomically(o.out / "contacts.csv", log.contacts_csv(model_names)));
    if (!s.ok()) return fail(s.message);
  }
  const TimingSummary timing = summarize_timing(durations, scene.haptic_rate);
  const TimingSummary cpu_timing = summarize_timing(cpu_durations, scene.haptic_rate);
  if (scene.outputs.timing) {
    const Status s =
        write(o.out / "timing.json",
              io::write_bytes_atomically(o.out / "timing.json",
                                         timing_json(timing, cpu_timing, o.scene.string())));
    if (!s.ok()) return fail(s.message);
  }
  {
    const Script recorded = record_script(received, session.tool().name);
    const Status s =
        write(o.out / kRecordedScriptName, write_script(recorded, o.out / kRecordedScriptName));
    if (!s.ok()) return fail(s.message);
  }
  if (scene.outputs.pictures) {
    io::Model all_before, all_after;
    for (std::size_t m = 0; m < after.size(); ++m) {
      for (const io::FaceRecord& f : before[m].faces) all_before.faces.push_back(f);
      for (const io::FaceRecord& f : after[m].faces) all_after.faces.push_back(f);
    }
    ToolPath path;
    for (const DeviceSample& s : received) {
      path.positions.push_back(s.position);
      path.engaged.push_back(s.engaged);
    }
    const Status s = write_session_pictures(all_before, all_after, path, log.times(), log.forces(),
                                            scene_name, o.out);
    if (!s.ok()) return fail(s.message);
    for (const char* name : {kBeforePicture, kAfterPicture, kForcePicture}) {
      written.push_back((o.out / name).string());
    }
  }
  const Status finished = journal.value().finish();
  if (!finished.ok()) return fail(finished.message);
  written.push_back(journal_path.string());

  std::printf("argil sculpt: %s, %lld ticks at %g Hz, %d strokes, tool %s\n", o.scene.c_str(),
              sampler.tick_count(), scene.haptic_rate, strokes, session.tool().name.c_str());
  if (timing.ticks > 0) {
    std::printf(
        "tick time: p50 %.1f us, p99 %.1f us, p99.9 %.1f us, max %.1f us (%lld ticks timed)\n"
        "tick thread CPU time: p50 %.1f us, p99 %.1f us, p99.9 %.1f us, max %.1f us\n",
        timing.p50 * 1e6, timing.p99 * 1e6, timing.p999 * 1e6, timing.max * 1e6, timing.ticks,
        cpu_timing.p50 * 1e6, cpu_timing.p99 * 1e6, cpu_timing.p999 * 1e6, cpu_timing.max * 1e6);
  }
  std::printf("files in %s:\n", o.out.c_str());
  for (const std::string& f : written) std::printf("  %s\n", f.c_str());
  return kExitOk;
}

}  // namespace argil::cli
