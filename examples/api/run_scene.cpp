// Runs a sculpting scene with a script, as `argil sculpt` does, stopping once
// the first stroke is finished (as a killed process would stop) and resuming
// from the journal: the second run replays the finished stroke and runs the
// rest. Writes the sculpted surfaces, logs and pictures to OUT.
// Usage: run_scene SCENE OUT [SCRIPT]
#include <cstdio>

#include "argil/sculpt.hpp"

namespace {

int report_error(const argil::Status& status) {
  std::fprintf(stderr, "run_scene: %s (%s)\n", status.message.c_str(),
               argil::to_string(status.code));
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: run_scene SCENE OUT [SCRIPT]\n");
    return 2;
  }
  namespace sculpt = argil::sculpt;
  sculpt::RunOptions options{
      .scene = argv[1], .script = argc > 3 ? argv[3] : "", .out = argv[2], .fresh = true};

  // First run: stop once a stroke is in the journal.
  options.progress_every = 10;
  options.on_progress = [](const sculpt::RunProgress& p) {
    return p.strokes >= 1 ? sculpt::RunControl::stop : sculpt::RunControl::proceed;
  };
  const argil::Result<sculpt::RunReport> first = sculpt::run_session(options);
  if (!first.ok()) return report_error(first.status());
  std::printf("first run stopped after %lld of %lld ticks, %d strokes journalled\n",
              first.value().ticks_run, first.value().ticks, first.value().strokes);

  // Second run: resume from the journal and finish.
  options.fresh = false;
  options.on_progress = {};
  const argil::Result<sculpt::RunReport> second = sculpt::run_session(options);
  if (!second.ok()) return report_error(second.status());
  const sculpt::RunReport& done = second.value();
  std::printf("resumed: %lld ticks replayed, %lld run; %d strokes (%d resumed)\n",
              done.ticks_replayed, done.ticks_run, done.strokes, done.strokes_resumed);
  std::printf("tick CPU time p50 %.1f us, p99.9 %.1f us\n", done.cpu_timing.p50 * 1e6,
              done.cpu_timing.p999 * 1e6);
  for (const auto& file : done.files) std::printf("  %s\n", file.c_str());
  // An ok run may still have outputs it could not write (a face STEP cannot take).
  for (const sculpt::OutputFailure& failed : done.failed_outputs) report_error(failed.status);
  return done.start == sculpt::RunStart::resumed && done.failed_outputs.empty() ? 0 : 1;
}
