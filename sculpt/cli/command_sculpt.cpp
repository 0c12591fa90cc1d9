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

#include "argil/sculpt/run/session_runner.hpp"
#include "commands.hpp"

namespace argil::cli {
namespace {

using namespace argil::sculpt;
using Clock = std::chrono::steady_clock;

int usage() {
  std::fprintf(stderr,
               "usage: argil sculpt SCENE [--script S] [--out DIR] [--tolerance E] [--fresh] "
               "[--realtime]\n"
               "  S: script (.json or .csv), default the scene's \"script\"\n"
               "  DIR: output folder, default out/<scene name>\n"
               "  E: eps in mm (> 0), overrides the scene's tolerance\n"
               "  --fresh: ignore an unfinished journal in DIR instead of resuming from it\n"
               "  --realtime: pace ticks at the haptic rate like a live device\n");
  return kExitUsage;
}

struct Options {
  std::filesystem::path scene, script, out;
  double tolerance = 0.0;  // 0: the scene's
  bool fresh = false;
  bool realtime = false;
};

int parse(const std::vector<std::string>& args, Options& o) {
  std::vector<std::string> positional;
  for (std::size_t k = 0; k < args.size(); ++k) {
    const std::string& a = args[k];
    const bool has_value = k + 1 < args.size();
    if (a == "--script" || a == "--out") {
      if (!has_value || args[k + 1].empty()) return usage();
      (a == "--script" ? o.script : o.out) = args[++k];
    } else if (a == "--tolerance") {
      if (!has_value) return usage();
      char* end = nullptr;
      o.tolerance = std::strtod(args[k + 1].c_str(), &end);
      if (end == args[k + 1].c_str() || *end != '\0' || !std::isfinite(o.tolerance) ||
          o.tolerance <= 0.0) {
        std::fprintf(stderr,
                     "argil sculpt: --tolerance needs a positive finite number [mm], got '%s'\n",
                     args[k + 1].c_str());
        return kExitUsage;
      }
      ++k;
    } else if (a == "--fresh") {
      o.fresh = true;
    } else if (a == "--realtime") {
      o.realtime = true;
    } else if (a.size() > 1 && a[0] == '-') {
      std::fprintf(stderr, "argil sculpt: unknown option '%s'\n", a.c_str());
      return usage();
    } else {
      positional.push_back(a);
    }
  }
  if (positional.size() != 1) return usage();
  o.scene = positional[0];
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

/// The run's summary on stdout: the counts, the tick-time percentiles and the files.
void print_report(const Options& o, const RunReport& report) {
  if (report.start == RunStart::resumed) {
    std::fprintf(stderr, "argil sculpt: resumed from %s: %zu records, %d strokes, ticks 0..%lld\n",
                 (report.out / "session.journal").c_str(), report.records_replayed,
                 report.strokes_resumed, report.ticks_replayed - 1);
  }
  for (const std::string& w : report.warnings)
    std::fprintf(stderr, "argil sculpt: %s\n", w.c_str());
  std::printf("argil sculpt: %s, %lld ticks at %g Hz, %d strokes, tool %s\n", o.scene.c_str(),
              report.ticks, report.haptic_rate, report.strokes, report.tool.c_str());
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

int run_sculpt(const std::vector<std::string>& args) {
  Options o;
  if (const int status = parse(args, o); status >= 0) return status;

  RunOptions options{
      .scene = o.scene, .script = o.script, .out = o.out, .fresh = o.fresh, .realtime = o.realtime};
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
  return kExitOk;
}

}  // namespace argil::cli
