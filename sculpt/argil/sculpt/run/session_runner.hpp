#pragma once
// Runs a sculpting session from files, as `argil sculpt` does: a scene and a
// script in; a journal kept while it runs, so a killed run resumes without
// losing a finished stroke; the sculpted surfaces, logs, timing and pictures
// out. Every input is checked before anything is written.

#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "argil/core/base/status.hpp"
#include "argil/sculpt/output/run_summary.hpp"
#include "argil/sculpt/output/tick_log.hpp"
#include "argil/sculpt/run/resume_plan.hpp"
#include "argil/sculpt/scene/scene.hpp"

namespace argil::sculpt {

/// Where a run is, for a progress display.
struct RunProgress {
  long long ticks_done = 0;   // ticks stepped so far, replayed ones included
  long long ticks_total = 0;  // ticks of the script
  int strokes = 0;            // strokes journalled so far, resumed ones included
};

/// What a progress callback asks of the run.
enum class RunControl { proceed, stop };

struct RunOptions {
  std::filesystem::path scene{};      // an argil.scene file
  std::filesystem::path script{};     // .json or .csv; empty: the scene's "script"
  std::filesystem::path out{};        // output folder; empty: out/<scene name>
  std::optional<double> tolerance{};  // eps [mm], > 0, in place of the scene's
  bool fresh = false;                 // start afresh even if `out` holds an unfinished journal
  bool realtime = false;  // pace live ticks at the haptic rate, as a device delivers them
  /// When > 0, once the session is made and before any tick, the process's
  /// heap is kept resident with this many bytes touched ahead
  /// (keep_heap_resident: process-wide and for the process's life; `argil
  /// sculpt` asks for 64 MB). 0 leaves the allocator alone.
  std::size_t resident_heap_bytes = 0;
  std::optional<OutputOptions> outputs{};  // files to write; empty: the scene's choice
  /// Called after every `progress_every`-th live tick and after the last one.
  /// Returning stop ends the run as a kill would: the journal keeps the strokes
  /// finished so far and nothing else is written, so a later run resumes.
  std::function<RunControl(const RunProgress&)> on_progress{};
  long long progress_every = 1;
};

/// An output a finished run could not write. The others were written; this one
/// was not (an existing file of that name is left as it was).
struct OutputFailure {
  std::filesystem::path file{};  // the output; for the pictures, the output folder
  Status status{};               // why: names the file and, for STEP and IGES, every failing face
};

/// What a run did.
struct RunReport {
  std::filesystem::path out{};       // the output folder
  std::string scene_name{};          // the scene file's stem, or its folder's name for scene.json
  std::string tool{};                // the tool the script holds first
  std::vector<std::string> tools{};  // every tool it holds (tool events), in order
  double haptic_rate = 0.0;          // [Hz]
  RunStart start = RunStart::no_journal;
  long long ticks = 0;               // ticks of the script
  long long ticks_replayed = 0;      // replayed from the journal: logged, not timed
  long long ticks_run = 0;           // stepped live and timed
  std::size_t records_replayed = 0;  // journal records (strokes, undo, redo) replayed
  int strokes = 0;                   // journalled strokes, resumed ones included
  int strokes_resumed = 0;           // of them, replayed from the journal
  bool stopped = false;              // on_progress asked to stop: the journal is left unfinished
  std::vector<std::filesystem::path> files{};   // written, in order; the journal last
  std::vector<OutputFailure> failed_outputs{};  // not written; empty when every output was
  TimingSummary wall_timing{};                  // wall time of each live Session::step [s]
  TimingSummary cpu_timing{};                   // the ticking thread's CPU time of each [s]
  /// The faces refined for the tool before the first tick (refinement_text()).
  std::vector<std::string> refinements{};
  /// The scene's (Scene::warnings), then what the run recovered from.
  std::vector<std::string> warnings{};
  /// What the run did to the deformable models (run_summary.hpp), also written
  /// as summary.json; empty when the run stopped early. Its warnings (the tool
  /// touched nothing, nothing changed) are not in `warnings`.
  RunSummary summary{};
};

/// Runs `options.scene` with its script to the end (or until on_progress asks
/// to stop), resuming from `options.out`'s journal unless `fresh`; see
/// plan_resume for when a journal is continued. Errors name the file and field
/// at fault. Codes: io_error, parse_error, invalid_argument for bad input;
/// failed_precondition when the folder's journal cannot be continued (another
/// run's, damaged, or not replaying to its recorded states): a fresh run would
/// proceed. A run that reaches its end writes every output it can: one that
/// fails (a sculpted face STEP or IGES cannot take) is listed in
/// `failed_outputs` of an ok report, the others and the finished journal are
/// written, so a caller must check both. The surfaces depend only on the
/// inputs: a resumed run ends with control points bit-identical to an
/// uninterrupted one.
Result<RunReport> run_session(const RunOptions& options);

}  // namespace argil::sculpt
