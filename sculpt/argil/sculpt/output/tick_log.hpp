#pragma once
// What a run logs per tick, and the files it becomes: forces.csv, contacts.csv
// and the per-tick timing summary (timing.json). Numbers are exact
// (shortest round-trip text, number_text).

#include <string>
#include <vector>

#include "argil/core/base/status.hpp"
#include "argil/sculpt/session/session.hpp"

namespace argil::sculpt {

/// Per-tick force and contact rows, kept in memory and written at the end.
class TickLog {
 public:
  /// Adds one tick.
  void add(const TickReport& report);

  /// "tick,time,fx,fy,fz,f,clamped,proxy_x,proxy_y,proxy_z,contacts,max_depth" and one row per
  /// tick.
  std::string forces_csv() const;
  /// "tick,time,model,face,u,v,x,y,z,depth,nx,ny,nz" and one row per contact.
  std::string contacts_csv(const std::vector<std::string>& model_names) const;

  const std::vector<long long>& ticks() const { return ticks_; }
  const std::vector<double>& times() const { return times_; }
  const std::vector<Eigen::Vector3d>& forces() const { return forces_; }
  /// Contacts of each tick.
  const std::vector<int>& contact_counts() const { return contact_counts_; }
  /// The scene tool held at each tick (TickReport::tool).
  const std::vector<int>& tools() const { return tools_; }
  std::size_t size() const { return times_.size(); }

 private:
  std::vector<long long> ticks_;
  std::vector<double> times_;
  std::vector<Eigen::Vector3d> forces_, proxies_;
  std::vector<char> clamped_;
  std::vector<int> contact_counts_;
  std::vector<int> tools_;
  std::vector<double> max_depths_;
  std::vector<std::pair<long long, ContactRecord>> contacts_;
  std::vector<double> contact_times_;
};

/// Order statistics of per-tick wall times [s].
struct TimingSummary {
  long long ticks = 0;
  double p50 = 0.0, p99 = 0.0, p999 = 0.0, max = 0.0, mean = 0.0;  // [s]
  double budget = 0.0;                                             // one haptic period 1 / rate [s]
  long long over_budget = 0;                                       // ticks slower than the budget
};

/// Nearest-rank percentiles (the smallest value with at least q of the
/// samples at or below it) of `durations` [s]; `rate_hz` sets the budget.
TimingSummary summarize_timing(std::vector<double> durations, double rate_hz);

/// The summaries as JSON (microseconds), with what was measured: wall time
/// (what a device waits for) at the top level, and the thread's CPU time
/// (the tick's own cost, without time the scheduler gave other processes).
std::string timing_json(const TimingSummary& wall, const TimingSummary& thread_cpu,
                        const std::string& scene_name);

}  // namespace argil::sculpt
