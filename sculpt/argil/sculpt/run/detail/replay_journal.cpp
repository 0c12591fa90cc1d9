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

/// An undo, redo or tool record: done again, and matched with the script's
/// next command.
Status replay_command(Session& session, const JournalRecord& record, std::size_t r,
                      const std::filesystem::path& journal_path, const ScriptSampler& sampler,
                      RunState& state) {
  const std::vector<ScriptSampler::Command>& commands = sampler.commands();
  const ScriptEvent kind = record.kind == JournalRecord::Kind::undo   ? ScriptEvent::undo
                           : record.kind == JournalRecord::Kind::redo ? ScriptEvent::redo
                                                                      : ScriptEvent::tool;
  const bool tools = static_cast<std::size_t>(record.tool) < session.scene().tools.size();
  if (state.commands.size() >= commands.size() || commands[state.commands.size()].event != kind ||
      (kind == ScriptEvent::tool &&
       (!tools || commands[state.commands.size()].tool !=
                      session.scene().tools[static_cast<std::size_t>(record.tool)].name))) {
    return Status::error(StatusCode::failed_precondition,
                         journal_path.string() + ": record " + std::to_string(r) + " is a " +
                             to_string(kind) + " the script does not have next (inputs changed?)");
  }
  const ScriptSampler::Command& command = commands[state.commands.size()];
  const Status done = kind == ScriptEvent::undo   ? session.undo()
                      : kind == ScriptEvent::redo ? session.redo()
                                                  : session.switch_tool(command.tool);
  if (!done.ok()) {
    return Status::error(StatusCode::failed_precondition,
                         journal_path.string() + ": " + done.message);
  }
  state.commands.push_back(command);
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
      const Status replayed = replay_command(session, record, r, journal_path, sampler, state);
      if (!replayed.ok()) return replayed;
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
