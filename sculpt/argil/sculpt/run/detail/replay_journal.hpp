#pragma once
// Internal to the runner: a resumed run's journal replayed through a fresh
// session, checking that each record reaches the state it recorded.

#include <filesystem>

#include "argil/core/base/status.hpp"
#include "argil/sculpt/run/detail/run_state.hpp"
#include "argil/sculpt/session/journal.hpp"
#include "argil/sculpt/session/session.hpp"

namespace argil::sculpt::detail {

/// Steps `session` through every record of `journal` (the samples of strokes,
/// undo and redo), logging each tick into `state` and each command as the
/// script's next (`sampler`'s commands, in order). Fails with
/// failed_precondition when a record skips ticks, does not replay to its
/// state hash, or is a command the script does not have next (the inputs
/// changed under the journal).
Status replay_journal(Session& session, const JournalContents& journal,
                      const std::filesystem::path& journal_path, const ScriptSampler& sampler,
                      RunState& state);

}  // namespace argil::sculpt::detail
