#include "argil/sculpt/view/session_replay.hpp"

#include <filesystem>
#include <nlohmann/json.hpp>
#include <system_error>
#include <utility>

#include "argil/core/base/number_text.hpp"
#include "argil/io/base/text_file.hpp"
#include "argil/sculpt/run/resume_plan.hpp"
#include "argil/sculpt/script/script.hpp"
#include "argil/sculpt/session/journal.hpp"
#include "argil/sculpt/session/session.hpp"

namespace argil::sculpt {
namespace {

// About this many frames at regular ticks when no interval is given.
constexpr long long kDefaultFrames = 60;

/// What the run left in its folder that the replay needs.
struct RunRecord {
  std::filesystem::path scene;
  double tolerance = 0.0;
  Script recorded;
  JournalContents journal;
};

Status folder_error(const std::filesystem::path& file, const std::string& what) {
  return Status::error(StatusCode::invalid_argument,
                       file.string() + ": " + what + " (not the output folder of a finished run)");
}

Result<RunRecord> read_run_record(const ReplayOptions& options) {
  RunRecord run;
  const std::filesystem::path summary_path = options.folder / "summary.json";
  Result<std::string> summary_text = io::read_text_file(summary_path);
  if (!summary_text.ok()) return folder_error(summary_path, "cannot be read");
  const nlohmann::json summary = nlohmann::json::parse(summary_text.value(), nullptr, false);
  if (summary.is_discarded() || !summary.is_object() ||
      summary.value("format", "") != "argil.summary" || !summary.contains("scene") ||
      !summary["scene"].is_string() || !summary.contains("tolerance_mm") ||
      !summary["tolerance_mm"].is_number()) {
    return folder_error(summary_path, "not an argil.summary with \"scene\" and \"tolerance_mm\"");
  }
  run.scene = options.scene;
  if (run.scene.empty()) {
    // The absolute path first: the path as given is relative to where the
    // run started, and from elsewhere it may name another run's scene (every
    // example's is scene.json). As given when the absolute one is gone (the
    // run's folder and scene moved together).
    run.scene = summary["scene"].get<std::string>();
    std::error_code ignored;
    if (summary.contains("scene_absolute") && summary["scene_absolute"].is_string()) {
      const std::filesystem::path absolute = summary["scene_absolute"].get<std::string>();
      if (std::filesystem::exists(absolute, ignored)) run.scene = absolute;
    }
  }
  run.tolerance = summary["tolerance_mm"].get<double>();
  Result<Script> recorded = read_script(options.folder / "recorded.csv");
  if (!recorded.ok()) return recorded.status();
  run.recorded = std::move(recorded).value();
  const std::filesystem::path journal_path = options.folder / "session.journal";
  JournalRead journal = read_journal(journal_path);
  if (!journal.ok()) return journal.status;
  if (!journal.contents.finished) return folder_error(journal_path, "the run did not finish");
  run.journal = std::move(journal.contents);
  return run;
}

/// The scene the run used, checked against the journal's hash of its bytes
/// and tolerance.
Result<Scene> read_run_scene(const RunRecord& run, const ReplayOptions& options) {
  Result<Scene> scene = read_scene(run.scene);
  if (!scene.ok()) {
    return Status::error(
        scene.status().code,
        scene.status().message + (options.scene.empty() ? " (the scene named in summary.json; give "
                                                          "the scene with --scene)"
                                                        : ""));
  }
  scene.value().tolerance = run.tolerance;
  Result<std::string> bytes = io::read_text_file(run.scene);
  if (!bytes.ok()) return bytes.status();
  const JournalHeader header =
      journal_header_for(bytes.value(), run.tolerance, "", scene.value().haptic_rate);
  if (header.scene_hash != run.journal.header.scene_hash) {
    return Status::error(StatusCode::failed_precondition,
                         run.scene.string() + ": the scene (or its tolerance " +
                             number_text(run.tolerance) + " mm) is not the one " +
                             (options.folder / "session.journal").string() +
                             " was run with: it changed since the run");
  }
  return scene;
}

/// The session's current faces of every deformable model (empty for rigid).
std::vector<io::Model> deformable_faces(const Session& session) {
  std::vector<io::Model> models(session.models().size());
  for (std::size_t m = 0; m < models.size(); ++m) {
    if (session.models()[m].spec.deformable) models[m] = session.current_faces(static_cast<int>(m));
  }
  return models;
}

void add_frame(const Session& session, long long tick, double time, std::string kind,
               std::vector<Eigen::Vector3d> contacts, SessionReplay& replay) {
  replay.frames.push_back({.tick = tick,
                           .time = time,
                           .kind = std::move(kind),
                           .models = deformable_faces(session),
                           .contacts = std::move(contacts)});
}

/// The states the journal recorded, to check the replay against: record r's
/// state is reached after `samples` ticks and `commands` undo or redo.
struct Checkpoint {
  long long samples = 0;
  std::size_t commands = 0;
  std::uint64_t state_hash = 0;
};

std::vector<Checkpoint> checkpoints_of(const JournalContents& journal) {
  std::vector<Checkpoint> checkpoints;
  Checkpoint at;
  for (const JournalRecord& record : journal.records) {
    at.samples += static_cast<long long>(record.samples.size());
    if (record.kind != JournalRecord::Kind::stroke) ++at.commands;
    at.state_hash = record.state_hash;
    checkpoints.push_back(at);
  }
  return checkpoints;
}

/// Steps the replay to the end, checking each journalled state on the way.
class Replayer {
 public:
  Replayer(Session& session, const ScriptSampler& sampler, std::vector<Checkpoint> checkpoints,
           SessionReplay& replay)
      : session_(session),
        sampler_(sampler),
        checkpoints_(std::move(checkpoints)),
        replay_(replay) {}

  Status run(long long every);
  /// Fails unless the replay reached every state the journal recorded.
  Status all_checked() const {
    if (next_checkpoint_ == checkpoints_.size()) return Status::success();
    return Status::error(StatusCode::failed_precondition,
                         "it does not reach the state of session.journal's record " +
                             std::to_string(next_checkpoint_ + 1) + " of " +
                             std::to_string(checkpoints_.size()) +
                             " (a changed recording, or another version of argil ran it?)");
  }

 private:
  Status apply_command(const ScriptSampler::Command& command, long long tick);
  Status check(long long samples_done);

  Session& session_;
  const ScriptSampler& sampler_;
  std::vector<Checkpoint> checkpoints_;
  std::size_t next_checkpoint_ = 0;
  std::size_t commands_done_ = 0;
  SessionReplay& replay_;
};

Status Replayer::check(long long samples_done) {
  while (next_checkpoint_ < checkpoints_.size() &&
         checkpoints_[next_checkpoint_].samples == samples_done &&
         checkpoints_[next_checkpoint_].commands == commands_done_) {
    if (checkpoints_[next_checkpoint_].state_hash != session_.state_hash()) {
      return Status::error(
          StatusCode::failed_precondition,
          "after tick " + std::to_string(samples_done - 1) +
              " the surfaces differ from the state session.journal recorded "
              "(record " +
              std::to_string(next_checkpoint_ + 1) +
              "): a model file changed since the run, or another version of argil ran it?");
    }
    ++next_checkpoint_;
  }
  return Status::success();
}

Status Replayer::apply_command(const ScriptSampler::Command& command, long long tick) {
  const bool undo = command.event == ScriptEvent::undo;
  const Status done = undo                                 ? session_.undo()
                      : command.event == ScriptEvent::redo ? session_.redo()
                                                           : session_.switch_tool(command.tool);
  if (!done.ok()) return done;
  ++commands_done_;
  if (command.event == ScriptEvent::tool) return check(tick);
  // The command's frame shows the surfaces it restored, at the tick it came
  // before (the tool is where the previous tick left it).
  const long long shown = std::max<long long>(tick - 1, 0);
  add_frame(session_, shown, tick_time(shown, replay_.haptic_rate), undo ? "undo" : "redo", {},
            replay_);
  return check(tick);
}

Status Replayer::run(long long every) {
  const std::vector<ScriptSampler::Command>& commands = sampler_.commands();
  std::size_t next_command = 0;
  const long long total = sampler_.tick_count();
  for (long long k = 0; k < total; ++k) {
    for (; next_command < commands.size() && commands[next_command].tick <= k; ++next_command) {
      const Status applied = apply_command(commands[next_command], k);
      if (!applied.ok()) return applied;
    }
    const DeviceSample sample = sampler_.sample(k);
    Result<TickReport> stepped = session_.step(sample);
    if (!stepped.ok()) return stepped.status();
    const TickReport& report = stepped.value();
    if (const Status checked = check(k + 1); !checked.ok()) return checked;
    replay_.time.push_back(report.time);
    replay_.device.push_back(sample.X_WD.p);
    replay_.orientation.push_back(sample.X_WD.R);
    replay_.proxy.push_back(report.proxy);
    replay_.engaged.push_back(sample.engaged);
    replay_.force.push_back(report.force);
    replay_.tool_index.push_back(report.tool);
    const char* kind = k + 1 == total           ? "end"
                       : report.stroke_finished ? "stroke end"
                       : (k + 1) % every == 0   ? "tick"
                                                : nullptr;
    if (kind == nullptr) continue;
    std::vector<Eigen::Vector3d> contacts;
    for (const ContactRecord& c : report.contacts) contacts.push_back(c.point);
    add_frame(session_, k, report.time, kind, std::move(contacts), replay_);
  }
  return Status::success();
}

}  // namespace

Result<SessionReplay> replay_session(const ReplayOptions& options) {
  Result<RunRecord> run = read_run_record(options);
  if (!run.ok()) return run.status();
  Result<Scene> scene = read_run_scene(run.value(), options);
  if (!scene.ok()) return scene.status();
  const Script& recorded = run.value().recorded;
  const std::vector<std::string> tools = tools_held(recorded);
  Result<Session> created =
      Session::create(scene.value(), recorded.tool, engaged_paths(recorded),
                      std::vector<std::string>(tools.begin() + 1, tools.end()));
  if (!created.ok()) {
    return Status::error(created.status().code,
                         run.value().scene.string() + ": " + created.status().message);
  }
  Session& session = created.value();
  SessionReplay replay;
  replay.scene_path = run.value().scene;
  replay.scene = scene.value();
  replay.tools = scene.value().tools;
  replay.haptic_rate = scene.value().haptic_rate;
  for (int m = 0; m < static_cast<int>(session.models().size()); ++m) {
    replay.before.push_back(session.current_faces(m));
    replay.file_faces.push_back(session.models()[static_cast<std::size_t>(m)].file_faces);
  }
  const ScriptSampler sampler(recorded, replay.haptic_rate);
  const long long every =
      options.every > 0
          ? options.every
          : std::max<long long>(1, (sampler.tick_count() + kDefaultFrames - 1) / kDefaultFrames);
  Replayer replayer(session, sampler, checkpoints_of(run.value().journal), replay);
  Status stepped = replayer.run(every);
  if (stepped.ok()) stepped = replayer.all_checked();
  if (!stepped.ok()) {
    return Status::error(
        stepped.code, (options.folder / "recorded.csv").string() + ": replay: " + stepped.message);
  }
  return replay;
}

}  // namespace argil::sculpt
