#include "argil/sculpt/run/resume_plan.hpp"

#include <cstdio>

#include "argil/sculpt/detail/fnv_hash.hpp"

namespace argil::sculpt {

const char* to_string(RunStart start) {
  switch (start) {
    case RunStart::no_journal:
      return "no_journal";
    case RunStart::fresh_requested:
      return "fresh_requested";
    case RunStart::previous_finished:
      return "previous_finished";
    case RunStart::torn_header:
      return "torn_header";
    case RunStart::resumed:
      return "resumed";
  }
  return "unknown";
}

JournalHeader journal_header_for(const std::string& scene_bytes, double tolerance,
                                 const std::string& script_bytes, double haptic_rate) {
  // "%a" is exact: any change of the tolerance changes the hash.
  char tolerance_text[40];
  std::snprintf(tolerance_text, sizeof tolerance_text, " tolerance=%a", tolerance);
  JournalHeader header;
  header.scene_hash = fnv1a64(scene_bytes + tolerance_text);
  header.script_hash = fnv1a64(script_bytes);
  header.haptic_rate = haptic_rate;
  return header;
}

Result<ResumePlan> plan_resume(const std::filesystem::path& journal_path,
                               const JournalHeader& inputs, bool fresh) {
  if (fresh) return ResumePlan{RunStart::fresh_requested, {}};
  if (!std::filesystem::exists(journal_path)) return ResumePlan{RunStart::no_journal, {}};
  JournalRead read = read_journal(journal_path);
  switch (read.fault) {
    case JournalFault::none:
      break;
    case JournalFault::torn_header:
      return ResumePlan{RunStart::torn_header, {}};
    case JournalFault::unreadable:
      return read.status;
    case JournalFault::not_a_journal:
    case JournalFault::damaged_record:
    case JournalFault::malformed_record:
    case JournalFault::record_after_end:
      return Status::error(StatusCode::failed_precondition, read.status.message);
  }
  if (read.contents.finished) return ResumePlan{RunStart::previous_finished, {}};
  const JournalHeader& h = read.contents.header;
  if (h.scene_hash != inputs.scene_hash || h.script_hash != inputs.script_hash ||
      h.haptic_rate != inputs.haptic_rate) {
    return Status::error(
        StatusCode::failed_precondition,
        journal_path.string() + ": an unfinished run of another scene, script or tolerance");
  }
  return ResumePlan{RunStart::resumed, std::move(read.contents)};
}

}  // namespace argil::sculpt
