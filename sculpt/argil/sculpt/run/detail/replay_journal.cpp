#include "argil/sculpt/run/detail/replay_journal.hpp"

#include <string>

namespace argil::sculpt::detail {
namespace {

Status replay_stroke(Session& session, const JournalRecord& record, std::size_t index,
                     const std::filesystem::path& journal_path, RunState& state) {
  for (const DeviceSample& s : record.samples) {
    if (s.tick != state.next_tick) {
      return Status::error(StatusCode::failed_precondition,
                           journal_path.string() + ": record " + std::to_string(index) +
                               " skips from tick " + std::to_string(state.next_tick) + " to " +
                               std::to_string(s.tick));
    }
    Result<TickReport> report = session.step(s);
    if (!report.ok()) return report.status();
    state.log.add(report.value());
    state.received.push_back(s);
    ++state.next_tick;
  }
  if (holds_stroke(record.samples)) ++state.strokes;
  return Status::success();
}

}  // namespace

Status replay_journal(Session& session, const JournalContents& journal,
                      const std::filesystem::path& journal_path, const ScriptSampler& sampler,
                      RunState& state) {
  for (std::size_t r = 0; r < journal.records.size(); ++r) {
    const JournalRecord& record = journal.records[r];
    if (record.kind == JournalRecord::Kind::stroke) {
      const Status replayed = replay_stroke(session, record, r, journal_path, state);
      if (!replayed.ok()) return replayed;
    } else {
      const Status done =
          record.kind == JournalRecord::Kind::undo ? session.undo() : session.redo();
      if (!done.ok()) {
        return Status::error(StatusCode::failed_precondition,
                             journal_path.string() + ": " + done.message);
      }
      // The script's next command is the one this record journalled.
      const std::vector<ScriptSampler::Command>& commands = sampler.commands();
      const ScriptEvent kind =
          record.kind == JournalRecord::Kind::undo ? ScriptEvent::undo : ScriptEvent::redo;
      if (state.commands.size() >= commands.size() ||
          commands[state.commands.size()].event != kind) {
        return Status::error(StatusCode::failed_precondition,
                             journal_path.string() + ": record " + std::to_string(r) + " is an " +
                                 to_string(kind) +
                                 " the script does not have next (inputs changed?)");
      }
      state.commands.push_back(commands[state.commands.size()]);
    }
    if (session.state_hash() != record.state_hash) {
      return Status::error(StatusCode::failed_precondition,
                           journal_path.string() + ": record " + std::to_string(r) +
                               " does not replay to the journalled state (inputs changed?)");
    }
  }
  return Status::success();
}

}  // namespace argil::sculpt::detail
