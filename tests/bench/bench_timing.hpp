#pragma once
// Timing helpers of the haptic-loop benchmark: thread CPU time, tick
// percentiles and medians of repeated runs.

#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <ctime>
#include <string>
#include <vector>

namespace argil::bench {

/// CPU time of this thread [us]: unlike wall time, it excludes time the
/// scheduler gave to other processes on a loaded machine.
inline double thread_cpu_us() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return 1e6 * static_cast<double>(ts.tv_sec) + 1e-3 * static_cast<double>(ts.tv_nsec);
}

struct Percentiles {
  double p50 = 0.0, p99 = 0.0, p999 = 0.0, max = 0.0;
};

/// Nearest-rank percentiles of per-tick times.
inline Percentiles percentiles(std::vector<double> us) {
  if (us.empty()) return {};
  std::sort(us.begin(), us.end());
  const auto at = [&](double q) {
    return us[std::min(us.size() - 1,
                       static_cast<std::size_t>(q * static_cast<double>(us.size())))];
  };
  return {at(0.5), at(0.99), at(0.999), us.back()};
}

/// Median of a few values (the upper middle one for an even count).
inline double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

/// Each percentile's median over repeated runs of the same case.
inline Percentiles median_of(const std::vector<Percentiles>& runs) {
  std::vector<double> p50, p99, p999, max;
  for (const Percentiles& r : runs) {
    p50.push_back(r.p50);
    p99.push_back(r.p99);
    p999.push_back(r.p999);
    max.push_back(r.max);
  }
  return {median(p50), median(p99), median(p999), median(max)};
}

/// A duration given in microseconds, in 3 significant digits: "84.2 us", "1.41 ms".
inline std::string time_text(double us) {
  char text[32];
  if (us >= 1000.0)
    std::snprintf(text, sizeof text, "%.3g ms", 1e-3 * us);
  else
    std::snprintf(text, sizeof text, "%.3g us", us);
  return text;
}

}  // namespace argil::bench
