#pragma once
// Runs a peer in a child process with a time limit, so a peer that hangs (or
// crashes) is reported instead of waited on or taking the benchmark down.

#include <functional>
#include <string>
#include <vector>

namespace argil::bench {

struct GuardedResult {
  enum class Outcome { returned, timed_out, crashed };
  Outcome outcome = Outcome::crashed;
  std::vector<double> payload;  // what the child sent back (when it returned)
  std::string detail;           // "signal 11", "no return in 30 s CPU"
};

/// Runs `work` in a forked child and returns the numbers it produced, or why
/// it did not: stopped after `limit_s` seconds of CPU time (or ten times that
/// in wall time), or died. The child's stderr is discarded.
GuardedResult run_guarded(const std::function<std::vector<double>()>& work, double limit_s);

}  // namespace argil::bench
