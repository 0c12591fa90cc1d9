// argil sculpt SCENE [--script S] [--out DIR] [--tolerance E] [--fresh] [--realtime]:
// runs a session from a scripted device and writes the sculpted surfaces, logs,
// timing and pictures. Resumes from DIR/session.journal after a crash.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "argil/core/base/resident_heap.hpp"
#include "argil/sculpt/run/session_runner.hpp"
#include "commands.hpp"

namespace argil::cli {
namespace {

using namespace argil::sculpt;
using Clock = std::chrono::steady_clock;

struct Options {
  std::filesystem::path scene, script, out;
  double tolerance = 0.0;  // 0: the scene's
  bool fresh = false;
  bool realtime = false;
};

/// Checks the command line; returns -1 when the run should go ahead with `o`
/// filled in, else the exit status.
int parse(const std::vector<std::string>& args, Options& o) {
  const ParseResult parsed = parse_arguments(sculpt_command(), args);
  if (!parsed.arguments) return parsed.exit_status;
  const Arguments& a = *parsed.arguments;
  o.scene = a.operands[0];
  o.script = a.text("--script").value_or("");
  o.out = a.text("--out").value_or("");
  o.tolerance = a.number("--tolerance").value_or(0.0);
  o.fresh = a.flag("--fresh");
  o.realtime = a.flag("--realtime");
  return -1;
}

int fail(const std::string& message) {
  std::fprintf(stderr, "argil sculpt: %s\n", message.c_str());
  return kExitFailure;
}

/// A one-line progress bar on stderr, drawn only on a terminal.
class ProgressBar {
 public:
  ProgressBar() : enabled_(isatty(STDERR_FILENO) == 1) {}
  void update(long long done, long long total, int strokes) {
    if (!enabled_) return;
    const Clock::time_point now = Clock::now();
    if (done < total && now - last_ < std::chrono::milliseconds(100)) return;
    last_ = now;
    drawn_ = true;
    const int width = 32;
    const double fraction =
        total > 0 ? static_cast<double>(done) / static_cast<double>(total) : 1.0;
    const int filled = static_cast<int>(fraction * width);
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.resize(width, '.');
    std::fprintf(stderr, "\r[%s] %3d%%  tick %lld/%lld  strokes %d", bar.c_str(),
                 static_cast<int>(fraction * 100.0), done, total, strokes);
    std::fflush(stderr);
  }
  void finish() {
    if (drawn_) std::fprintf(stderr, "\n");
  }

 private:
  bool enabled_;
  bool drawn_ = false;
  Clock::time_point last_{};
};

/// The run's summary on stdout: the counts, what changed, the tick-time
/// percentiles and the files; its warnings on stderr.
void print_report(const Options& o, const RunReport& report) {
  if (report.start == RunStart::resumed) {
    std::fprintf(stderr, "argil sculpt: resumed from %s: %zu records, %d strokes, ticks 0..%lld\n",
                 (report.out / "session.journal").c_str(), report.records_replayed,
                 report.strokes_resumed, report.ticks_replayed - 1);
  }
  for (const std::string& w : report.warnings)
    std::fprintf(stderr, "argil sculpt: %s\n", w.c_str());
  std::string tools;
  for (const std::string& name : report.tools) tools += (tools.empty() ? "" : ", ") + name;
  std::printf("argil sculpt: %s, %lld ticks at %g Hz, %d strokes, tool%s %s\n", o.scene.c_str(),
              report.ticks, report.haptic_rate, report.strokes, report.tools.size() > 1 ? "s" : "",
              tools.c_str());
  if (!report.refinements.empty())
    std::printf("refined for the tool (exactly: the shape does not change):\n");
  for (const std::string& r : report.refinements) std::printf("  %s\n", r.c_str());
  for (const std::string& line : summary_lines(report.summary)) std::printf("%s\n", line.c_str());
  for (const std::string& w : report.summary.warnings)
    std::fprintf(stderr, "argil sculpt: warning: %s\n", w.c_str());
  const TimingSummary& wall = report.wall_timing;
  const TimingSummary& cpu = report.cpu_timing;
  if (wall.ticks > 0) {
    std::printf(
        "tick time: p50 %.1f us, p99 %.1f us, p99.9 %.1f us, max %.1f us (%lld ticks timed)\n"
        "tick thread CPU time: p50 %.1f us, p99 %.1f us, p99.9 %.1f us, max %.1f us\n",
        wall.p50 * 1e6, wall.p99 * 1e6, wall.p999 * 1e6, wall.max * 1e6, wall.ticks, cpu.p50 * 1e6,
        cpu.p99 * 1e6, cpu.p999 * 1e6, cpu.max * 1e6);
  }
  std::printf("files in %s:\n", report.out.c_str());
  for (const std::filesystem::path& f : report.files) std::printf("  %s\n", f.c_str());
}

}  // namespace

const CommandDeclaration& sculpt_command() {
  static const CommandDeclaration spec{
      .name = "sculpt",
      .operands = {"SCENE"},
      .summary = "run a sculpting session: a scene's tool driven by a script",
      .description =
          "Writes the sculpted surfaces (STEP, IGES, JSON), forces.csv, contacts.csv,\n"
          "timing.json, summary.json, recorded.csv and pictures to DIR. Prints what\n"
          "changed: the largest inward (negative) and outward displacement along the\n"
          "face normal, the area that moved more than eps, the peak force and the\n"
          "ticks over budget; warns when the tool touched nothing or nothing changed. An "
          "interrupted run resumes\n"
          "from DIR/session.journal. An output that cannot be written (a sculpted face\n"
          "STEP or IGES cannot take) is named on stderr with exit status 1; the other\n"
          "outputs are written all the same. The material presets a scene can name:\n"
          "argil materials.",
      .options = {{.name = "--script",
                   .argument = "S",
                   .kind = ValueKind::text,
                   .description = "the device script (.json or .csv)",
                   .default_text = "the scene's \"script\""},
                  {.name = "--out",
                   .argument = "DIR",
                   .kind = ValueKind::text,
                   .description = "the output folder",
                   .default_text = "out/<scene name>"},
                  {.name = "--tolerance",
                   .argument = "E",
                   .kind = ValueKind::number,
                   .description = "eps, the contact distance; overrides the scene's",
                   .range = kPositiveFinite,
                   .unit = "mm",
                   .default_text = "the scene's \"tolerance\""},
                  {.name = "--fresh",
                   .description = "ignore an unfinished journal in DIR instead of resuming from it",
                   .default_text = "off"},
                  {.name = "--realtime",
                   .description = "pace ticks at the haptic rate like a live device",
                   .default_text = "off"}},
  };
  return spec;
}

int run_sculpt(const std::vector<std::string>& args) {
  Options o;
  if (const int status = parse(args, o); status >= 0) return status;

  RunOptions options{.scene = o.scene,
                     .script = o.script,
                     .out = o.out,
                     .fresh = o.fresh,
                     .realtime = o.realtime,
                     .resident_heap_bytes = kHapticHeapReserve};
  if (o.tolerance > 0.0) options.tolerance = o.tolerance;
  ProgressBar progress;
  options.on_progress = [&progress](const RunProgress& p) {
    progress.update(p.ticks_done, p.ticks_total, p.strokes);
    return RunControl::proceed;
  };
  const Result<RunReport> report = run_session(options);
  progress.finish();
  if (!report.ok()) {
    const Status& error = report.status();
    // The folder's journal blocks the run; a fresh run would discard it.
    if (error.code == StatusCode::failed_precondition) {
      return fail(error.message + "; rerun with --fresh to discard the journal");
    }
    return fail(error.message);
  }
  print_report(o, report.value());
  // Every other output is written; each missing one is an error of the run.
  const std::vector<OutputFailure>& failed = report.value().failed_outputs;
  for (const OutputFailure& f : failed)
    std::fprintf(stderr, "argil sculpt: %s\n", f.status.message.c_str());
  if (failed.empty()) return kExitOk;
  std::fprintf(stderr, "argil sculpt: %zu of %zu outputs not written\n", failed.size(),
               failed.size() + report.value().files.size());
  return kExitFailure;
}

}  // namespace argil::cli
