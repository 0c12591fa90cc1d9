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

int usage() {
  std::fprintf(stderr,
               "usage: argil sculpt SCENE [--script S] [--out DIR] [--tolerance E] [--fresh] "
               "[--realtime]\n"
               "  S: script (.json or .csv), default the scene's \"script\"\n"
               "  DIR: output folder, default out/<scene name>\n"
               "  E: eps in mm (> 0), overrides the scene's tolerance\n"
               "  --fresh: ignore an unfinished journal in DIR instead of resuming from it\n"
               "  --realtime: pace ticks at the haptic rate like a live device\n");
  return kExitUsage;
}

struct Options {
  std::filesystem::path scene, script, out;
  double tolerance = 0.0;  // 0: the scene's
  bool fresh = false;
  bool realtime = false;
};

int parse(const std::vector<std::string>& args, Options& o) {
  std::vector<std::string> positional;
  for (std::size_t k = 0; k < args.size(); ++k) {
    const std::string& a = args[k];
    const bool has_value = k + 1 < args.size();
    if (a == "--script" || a == "--out") {
      if (!has_value || args[k + 1].empty()) return usage();
      (a == "--script" ? o.script : o.out) = args[++k];
    } else if (a == "--tolerance") {
      if (!has_value) return usage();
      char* end = nullptr;
      o.tolerance = std::strtod(args[k + 1].c_str(), &end);
      if (end == args[k + 1].c_str() || *end != '\0' || !std::isfinite(o.tolerance) ||
          o.tolerance <= 0.0) {
        std::fprintf(stderr,
                     "argil sculpt: --tolerance needs a positive finite number [mm], got '%s'\n",
                     args[k + 1].c_str());
        return kExitUsage;
      }
      ++k;
    } else if (a == "--fresh") {
      o.fresh = true;
    } else if (a == "--realtime") {
      o.realtime = true;
    } else if (a.size() > 1 && a[0] == '-') {
      std::fprintf(stderr, "argil sculpt: unknown option '%s'\n", a.c_str());
      return usage();
    } else {
      positional.push_back(a);
    }
  }
  if (positional.size() != 1) return usage();
  o.scene = positional[0];
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
  const double ticks = script.keyframes.back().t * scene.haptic_rate;
  if (ticks > kMaxTicks) {
    char message[160];
    std::snprintf(
        message, sizeof message,
        ": keyframes[%zu].t: the script lasts %.17g s, %.3g ticks at %g Hz (at most %.0f)",
        script.keyframes.size() - 1, script.keyframes.back().t, ticks, scene.haptic_rate,
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
  header.scene_hash = input_hash(scene_bytes + tolerance_text);
  header.script_hash = input_hash(script_bytes);
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
    const OutputOptions& out = scene.outputs;
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
      path.positions.push_back(s.X_WD.p);
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
