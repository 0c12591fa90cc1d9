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
/// undo and redo), logging each tick into `state`. Fails with
/// failed_precondition when a record skips ticks or does not replay to its
/// state hash (the inputs changed under the journal).
Status replay_journal(Session& session, const JournalContents& journal,
                      const std::filesystem::path& journal_path, RunState& state);

}  // namespace argil::sculpt::detail
