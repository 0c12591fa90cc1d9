#pragma once
// The session journal: an append-only text file of finished strokes, so a run
// killed at any moment (kill -9, power loss) resumes without losing a finished
// stroke. Each record holds every device sample since the previous record (the
// stroke and the moves before it) and a hash of the control points after it;
// resuming replays the samples through a fresh Session, which is deterministic,
// and checks the hashes. Every record is one line ending in its own checksum and
// is fsync'd before the next tick, so a torn last line is detected and dropped.
// Format: docs/formats.md.

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "argil/core/base/status.hpp"
#include "argil/sculpt/script/script.hpp"

namespace argil::sculpt {

/// What a journal was written for: a run resumes only with the same inputs.
struct JournalHeader {
  std::uint64_t scene_hash = 0;   // of the scene file's bytes
  std::uint64_t script_hash = 0;  // of the script's bytes
  double haptic_rate = 0.0;       // [Hz]
};

/// One journal entry: the samples of ticks first_tick .. first_tick + n - 1
/// (consecutive), or an undo, redo or tool change (Session::switch_tool).
struct JournalRecord {
  enum class Kind { stroke, undo, redo, tool };
  Kind kind = Kind::stroke;
  int tool = -1;                      // Kind::tool: the scene tool's index
  std::vector<DeviceSample> samples;  // stroke: consecutive ticks; empty for commands
  std::uint64_t state_hash = 0;       // Session::state_hash() after the record
};

/// A journal as read back: the valid records, and whether the run had finished.
struct JournalContents {
  JournalHeader header;
  std::vector<JournalRecord> records;
  bool finished = false;             // an "end" record: nothing to resume
  std::size_t valid_bytes = 0;       // length of the intact prefix
  bool dropped_torn_record = false;  // a partial last line was ignored
};

/// Why a journal file could not be read; callers decide on this, never on the
/// message text.
enum class JournalFault {
  none,              // read: `contents` holds the intact prefix
  unreadable,        // the file cannot be opened or read
  torn_header,       // empty, or its header line is torn: killed before the first record
  not_a_journal,     // an intact first line that is not a journal header
  damaged_record,    // a checksum-failing line before intact ones: corruption, not a crash
  malformed_record,  // an intact line that is not a record
  record_after_end,  // a record after the "end" record
};

/// Name of a fault, for messages and test output ("torn_header").
const char* to_string(JournalFault fault);

/// A journal as read back, or why it could not be.
struct [[nodiscard]] JournalRead {
  JournalFault fault = JournalFault::none;
  Status status;             // the error naming the file and line; ok iff fault is none
  JournalContents contents;  // meaningful iff ok()
  bool ok() const { return fault == JournalFault::none; }
};

/// Reads a journal. A torn (partial or checksum-failing) last line is dropped;
/// a damaged line before intact ones is an error naming the line.
JournalRead read_journal(const std::filesystem::path& path);

/// Appends records durably (write, flush, fsync). Not copyable; closes on destruction.
class JournalWriter {
 public:
  /// Starts a new journal (replacing any file at `path`) with `header`.
  static Result<JournalWriter> create(const std::filesystem::path& path,
                                      const JournalHeader& header);
  /// Continues an existing journal after its intact prefix (a torn tail is cut off).
  static Result<JournalWriter> append_to(const std::filesystem::path& path,
                                         const JournalContents& contents);
  JournalWriter(JournalWriter&& other) noexcept;
  JournalWriter& operator=(JournalWriter&& other) noexcept;
  JournalWriter(const JournalWriter&) = delete;
  JournalWriter& operator=(const JournalWriter&) = delete;
  ~JournalWriter();

  Status append(const JournalRecord& record);
  /// Marks the run finished: a later run starts afresh instead of resuming.
  Status finish();

 private:
  JournalWriter(std::FILE* file, std::filesystem::path path)
      : file_(file), path_(std::move(path)) {}
  Status write_line(const std::string& body);

  std::FILE* file_ = nullptr;
  std::filesystem::path path_;
};

}  // namespace argil::sculpt
