#include "argil/sculpt/run/session_runner.hpp"

#include <system_error>
#include <utility>

#include "argil/core/base/resident_heap.hpp"
#include "argil/sculpt/run/detail/live_ticks.hpp"
#include "argil/sculpt/run/detail/replay_journal.hpp"
#include "argil/sculpt/run/detail/run_inputs.hpp"
#include "argil/sculpt/run/detail/run_outputs.hpp"
#include "argil/sculpt/run/detail/run_state.hpp"

namespace argil::sculpt {
namespace {

using detail::RunInputs;
using detail::RunState;

constexpr const char* kJournalName = "session.journal";

/// The journal to write into, and how the run starts.
struct OpenedJournal {
  ResumePlan plan;
  JournalWriter writer;
};

Result<OpenedJournal> open_journal(const RunInputs& in, bool fresh) {
  const std::filesystem::path path = in.out / kJournalName;
  const JournalHeader header =
      journal_header_for(in.scene_bytes, in.scene.tolerance, in.script_bytes, in.scene.haptic_rate);
  Result<ResumePlan> plan = plan_resume(path, header, fresh);
  if (!plan.ok()) return plan.status();
  Result<JournalWriter> writer = plan.value().start == RunStart::resumed
                                     ? JournalWriter::append_to(path, plan.value().journal)
                                     : JournalWriter::create(path, header);
  if (!writer.ok()) return writer.status();
  return OpenedJournal{std::move(plan).value(), std::move(writer).value()};
}

std::vector<std::string> start_warnings(const ResumePlan& plan) {
  std::vector<std::string> warnings;
  if (plan.start == RunStart::torn_header) {
    warnings.push_back("the journal's header was torn (killed at its start): started afresh");
  }
  if (plan.start == RunStart::resumed && plan.journal.dropped_torn_record) {
    warnings.push_back("dropped the journal's torn last record (killed while writing it)");
  }
  return warnings;
}

/// Replays the journal when resuming; fills the report's resume fields.
Status resume(Session& session, const OpenedJournal& journal, const RunInputs& in,
              const ScriptSampler& sampler, RunState& state, RunReport& report) {
  report.start = journal.plan.start;
  report.warnings = in.scene.warnings;
  for (std::string& w : start_warnings(journal.plan)) report.warnings.push_back(std::move(w));
  if (journal.plan.start != RunStart::resumed) return Status::success();
  const Status replayed =
      detail::replay_journal(session, journal.plan.journal, in.out / kJournalName, sampler, state);
  if (!replayed.ok()) return replayed;
  report.records_replayed = journal.plan.journal.records.size();
  report.ticks_replayed = state.next_tick;
  report.strokes_resumed = state.strokes;
  return Status::success();
}

/// The session with the scene's models loaded, and the output folder made.
Result<Session> prepare(const RunInputs& in) {
  const std::vector<std::string> tools = tools_held(in.script);
  Result<Session> created =
      Session::create(in.scene, in.script.tool, engaged_paths(in.script),
                      std::vector<std::string>(tools.begin() + 1, tools.end()));
  if (!created.ok()) {
    return Status::error(created.status().code,
                         in.scene_path.string() + ": " + created.status().message);
  }
  std::error_code ec;
  std::filesystem::create_directories(in.out, ec);
  if (ec) {
    return Status::error(StatusCode::io_error,
                         in.out.string() + ": cannot create the output folder: " + ec.message());
  }
  return created;
}

/// Each face of the deformable models, as `before` holds it and as it is now.
std::vector<SculptedFace> sculpted_faces(const Session& session,
                                         const std::vector<io::Model>& before) {
  std::vector<SculptedFace> faces;
  for (std::size_t m = 0; m < session.models().size(); ++m) {
    const LoadedModel& loaded = session.models()[m];
    if (!loaded.spec.deformable) continue;
    const io::Model after = session.current_faces(static_cast<int>(m));
    for (std::size_t f = 0; f < after.faces.size(); ++f) {
      faces.push_back({.model = loaded.spec.name,
                       .face = loaded.file_faces[f],
                       .before = before[m].faces[f].surface,
                       .after = after.faces[f].surface,
                       .trim = loaded.trims[f],
                       .reversed = before[m].faces[f].reversed});
    }
  }
  return faces;
}

/// The faces each model's scene names, as they are now (parallel to
/// LoadedModel::file_faces).
std::vector<io::Model> current_faces(const Session& session) {
  std::vector<io::Model> models;
  for (int m = 0; m < static_cast<int>(session.models().size()); ++m) {
    models.push_back(session.current_faces(m));
  }
  return models;
}

}  // namespace

Result<RunReport> run_session(const RunOptions& options) {
  Result<RunInputs> loaded = detail::load_run_inputs(options);
  if (!loaded.ok()) return loaded.status();
  const RunInputs& in = loaded.value();
  Result<Session> prepared = prepare(in);
  if (!prepared.ok()) return prepared.status();
  Session& session = prepared.value();
  // After the session is made (its own memory stays its own), before any tick.
  if (options.resident_heap_bytes > 0) keep_heap_resident(options.resident_heap_bytes);
  const std::vector<io::Model> before = current_faces(session);
  Result<OpenedJournal> journal = open_journal(in, options.fresh);
  if (!journal.ok()) return journal.status();

  const ScriptSampler sampler(in.script, in.scene.haptic_rate);
  RunReport report{.out = in.out,
                   .scene_name = in.scene_name,
                   .tool = session.tool().name,
                   .haptic_rate = in.scene.haptic_rate,
                   .ticks = sampler.tick_count()};
  report.tools = {report.tool};
  for (const std::string& name : tools_held(in.script)) {
    if (!name.empty() && name != report.tool) report.tools.push_back(name);
  }
  for (const FaceRefinement& r : session.refinements())
    report.refinements.push_back(refinement_text(r));
  RunState state;
  const Status resumed = resume(session, journal.value(), in, sampler, state, report);
  if (!resumed.ok()) return resumed;
  Result<detail::LoopEnd> ended =
      detail::run_live_ticks(session, sampler, journal.value().writer, options, state);
  if (!ended.ok()) return ended.status();
  report.ticks_run = state.next_tick - report.ticks_replayed;
  report.strokes = state.strokes;
  report.wall_timing = summarize_timing(state.wall_s, in.scene.haptic_rate);
  report.cpu_timing = summarize_timing(state.cpu_s, in.scene.haptic_rate);
  report.stopped = ended.value() == detail::LoopEnd::stopped;
  if (report.stopped) return report;

  report.summary =
      summarize_run(sculpted_faces(session, before), state.log, state.wall_s, state.cpu_s,
                    {.tolerance = in.scene.tolerance, .haptic_rate = in.scene.haptic_rate});
  report.summary.refinements = report.refinements;
  detail::RunOutputs outputs = detail::write_run_outputs(
      in, session, before, state, report.wall_timing, report.cpu_timing, report.summary);
  report.files = std::move(outputs.files);
  report.failed_outputs = std::move(outputs.failures);
  for (std::string& w : outputs.warnings) report.warnings.push_back(std::move(w));
  const Status finished = journal.value().writer.finish();
  if (!finished.ok()) return finished;
  report.files.push_back(in.out / kJournalName);
  return report;
}

}  // namespace argil::sculpt
