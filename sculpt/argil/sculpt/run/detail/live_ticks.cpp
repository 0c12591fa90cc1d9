#include "argil/sculpt/run/detail/live_ticks.hpp"

#include <chrono>
#include <ctime>
#include <thread>

#include "argil/core/base/number_text.hpp"

namespace argil::sculpt::detail {
namespace {

using Clock = std::chrono::steady_clock;

/// CPU time of the calling thread [s]: a tick's own cost, excluding preemption.
double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

/// One timed step, logged into `state`.
Result<TickReport> timed_step(Session& session, const DeviceSample& sample, RunState& state) {
  const double cpu0 = thread_cpu_seconds();
  const Clock::time_point t0 = Clock::now();
  Result<TickReport> report = session.step(sample);
  const Clock::time_point t1 = Clock::now();
  const double cpu1 = thread_cpu_seconds();
  if (!report.ok()) return report;
  state.wall_s.push_back(std::chrono::duration<double>(t1 - t0).count());
  state.cpu_s.push_back(cpu1 - cpu0);
  state.log.add(report.value());
  state.received.push_back(sample);
  state.unjournalled.push_back(sample);
  return report;
}

/// Appends the samples since the last record, with the state they lead to;
/// a record holding an engaged sample counts as a stroke.
Status journal_stroke(Session& session, JournalWriter& journal, RunState& state) {
  JournalRecord record;
  record.samples = std::move(state.unjournalled);
  state.unjournalled.clear();
  record.state_hash = session.state_hash();
  const Status appended = journal.append(record);
  if (appended.ok() && holds_stroke(record.samples)) ++state.strokes;
  return appended;
}

/// The script's undo, redo or tool change before a tick: the samples since
/// the last record are journalled first, so a resume replays them, then the
/// command and its record. Errors name the keyframe ("nothing to undo").
Status apply_command(Session& session, JournalWriter& journal, const ScriptSampler& sampler,
                     const ScriptSampler::Command& command, RunState& state) {
  if (!state.unjournalled.empty()) {
    const Status flushed = journal_stroke(session, journal, state);
    if (!flushed.ok()) return flushed;
  }
  const Status done = command.event == ScriptEvent::undo   ? session.undo()
                      : command.event == ScriptEvent::redo ? session.redo()
                                                           : session.switch_tool(command.tool);
  if (!done.ok()) {
    return Status::error(
        done.code, "script keyframe " + std::to_string(command.keyframe) +
                       " (t = " + number_text(sampler.script().keyframes[command.keyframe].t) +
                       " s): " + to_string(command.event) + ": " + done.message);
  }
  JournalRecord record;
  record.kind = command.event == ScriptEvent::undo   ? JournalRecord::Kind::undo
                : command.event == ScriptEvent::redo ? JournalRecord::Kind::redo
                                                     : JournalRecord::Kind::tool;
  record.tool = session.scene().tool_index(command.tool);
  record.state_hash = session.state_hash();
  const Status appended = journal.append(record);
  if (appended.ok()) state.commands.push_back(command);
  return appended;
}

bool progress_due(const RunOptions& options, long long done, long long total) {
  if (!options.on_progress) return false;
  const long long every = options.progress_every > 0 ? options.progress_every : 1;
  return done == total || done % every == 0;
}

}  // namespace

Result<LoopEnd> run_live_ticks(Session& session, const ScriptSampler& sampler,
                               JournalWriter& journal, const RunOptions& options, RunState& state) {
  const long long first = state.next_tick;
  const long long total = sampler.tick_count();
  const double rate = session.scene().haptic_rate;
  const Clock::time_point start = Clock::now();
  const std::vector<ScriptSampler::Command>& commands = sampler.commands();
  for (long long k = first; k < total; ++k) {
    // Commands are journalled in order: those a resume replayed are done.
    while (state.commands.size() < commands.size() && commands[state.commands.size()].tick <= k) {
      const Status applied =
          apply_command(session, journal, sampler, commands[state.commands.size()], state);
      if (!applied.ok()) return applied;
    }
    const DeviceSample sample = sampler.sample(k);
    if (options.realtime) {
      std::this_thread::sleep_until(
          start + std::chrono::duration_cast<Clock::duration>(
                      std::chrono::duration<double>(static_cast<double>(k - first) / rate)));
    }
    Result<TickReport> report = timed_step(session, sample, state);
    if (!report.ok()) return report.status();
    state.next_tick = k + 1;
    // A stroke is journalled when it finishes, and so is one the script ends in.
    if (report.value().stroke_finished || (k + 1 == total && sample.engaged)) {
      const Status appended = journal_stroke(session, journal, state);
      if (!appended.ok()) return appended;
    }
    if (progress_due(options, k + 1, total) &&
        options.on_progress({k + 1, total, state.strokes}) == RunControl::stop) {
      return LoopEnd::stopped;
    }
  }
  return LoopEnd::finished;
}

}  // namespace argil::sculpt::detail
