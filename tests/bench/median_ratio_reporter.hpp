#pragma once
// A console reporter that also keeps each benchmark's median time, so a
// benchmark program can print ratios between peers measured in the same run.

#include <benchmark/benchmark.h>

#include <cstdio>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace argil::bench {

class MedianRatioReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs) {
      if (run.aggregate_name == "median") {
        const std::string& args = run.run_name.args;
        medians_[run.run_name.function_name + (args.empty() ? "" : "/" + args)] =
            run.GetAdjustedRealTime();
        unit_ = benchmark::GetTimeUnitString(run.time_unit);
      }
    }
    ConsoleReporter::ReportRuns(runs);
  }

  /// Median real time of a benchmark in the run (its display unit), or a
  /// negative number when it did not run (filtered out).
  double median(const std::string& name) const {
    const auto it = medians_.find(name);
    return it == medians_.end() ? -1.0 : it->second;
  }
  const std::string& unit() const { return unit_; }

  /// Prints "numerator / denominator = ratio" for each pair found in the run.
  void print_ratios(const std::vector<std::pair<std::string, std::string>>& pairs) const {
    std::printf("\nMedian ratios (same run):\n");
    for (const auto& [slow, fast] : pairs) {
      const auto a = medians_.find(slow);
      const auto b = medians_.find(fast);
      if (a == medians_.end() || b == medians_.end()) continue;
      std::printf("  %-40s / %-40s = %6.2fx  (%.3g %s vs %.3g %s)\n", slow.c_str(), fast.c_str(),
                  a->second / b->second, a->second, unit_.c_str(), b->second, unit_.c_str());
    }
  }

 private:
  std::map<std::string, double> medians_;
  std::string unit_;
};

/// Runs the registered benchmarks with the reporter, then prints the ratios,
/// then calls `after` (if given) for tables built from the medians.
inline int run_with_ratios(int argc, char** argv,
                           const std::vector<std::pair<std::string, std::string>>& pairs,
                           const std::function<void(const MedianRatioReporter&)>& after = {}) {
  benchmark::Initialize(&argc, argv);
  MedianRatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  reporter.print_ratios(pairs);
  if (after) after(reporter);
  benchmark::Shutdown();
  return 0;
}

}  // namespace argil::bench
