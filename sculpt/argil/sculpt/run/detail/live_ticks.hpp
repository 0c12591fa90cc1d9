#pragma once
// Internal to the runner: the live part of a run, one timed Session::step per
// scripted tick, each finished stroke journalled before the next tick.

#include "argil/core/base/status.hpp"
#include "argil/sculpt/run/detail/run_state.hpp"
#include "argil/sculpt/run/session_runner.hpp"
#include "argil/sculpt/script/script.hpp"
#include "argil/sculpt/session/journal.hpp"
#include "argil/sculpt/session/session.hpp"

namespace argil::sculpt::detail {

enum class LoopEnd { finished, stopped };

/// Steps ticks state.next_tick .. sampler.tick_count() - 1, timing each step
/// (wall and thread CPU time) and appending a journal record when a stroke
/// finishes or the script ends in one. Paced at the haptic rate when
/// options.realtime; reports progress through options.on_progress, which may
/// stop the run.
Result<LoopEnd> run_live_ticks(Session& session, const ScriptSampler& sampler,
                               JournalWriter& journal, const RunOptions& options, RunState& state);

}  // namespace argil::sculpt::detail
