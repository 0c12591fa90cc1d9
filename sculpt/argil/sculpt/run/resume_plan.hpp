#pragma once
// How a run starts from its output folder's journal: afresh, or by resuming an
// unfinished run of the same inputs. Decided on journal fault codes and input
// hashes, never on message text.

#include <filesystem>
#include <string>

#include "argil/core/base/status.hpp"
#include "argil/sculpt/session/journal.hpp"

namespace argil::sculpt {

/// How a run starts.
enum class RunStart {
  no_journal,         // afresh: the folder holds no journal
  fresh_requested,    // afresh: the caller asked to replace any journal
  previous_finished,  // afresh: the journal's run had finished (its end record)
  torn_header,        // afresh: killed while writing the header, so nothing to resume
  resumed,            // the journal's records are replayed, then the run continues
};

/// Name of a start, for messages and test output ("torn_header").
const char* to_string(RunStart start);

/// The decision, and the journal to continue when resuming.
struct ResumePlan {
  RunStart start = RunStart::no_journal;
  JournalContents journal;  // read back; records to replay when start is resumed
};

/// The header a journal of these inputs carries: hashes of the scene file's
/// bytes with the effective tolerance eps [mm] (an override changes the run),
/// of the script's bytes, and the haptic rate [Hz].
JournalHeader journal_header_for(const std::string& scene_bytes, double tolerance,
                                 const std::string& script_bytes, double haptic_rate);

/// Decides how a run of `inputs` starts with its journal at `journal_path`.
/// `fresh` starts afresh whatever the folder holds. Fails with
/// failed_precondition when the journal is an unfinished run of other inputs
/// (scene, tolerance, script or rate) or cannot be continued (damaged, not a
/// journal): starting fresh would discard it. An unreadable file is io_error.
Result<ResumePlan> plan_resume(const std::filesystem::path& journal_path,
                               const JournalHeader& inputs, bool fresh);

}  // namespace argil::sculpt
