// Per-tick time of the press-and-drag stroke (docs/benchmarks.md, "Full haptic tick").
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "bench_timing.hpp"
#include "haptic_loop_sections.hpp"

namespace argil::bench {

namespace {

struct CaseSummary {
  std::string name;
  Percentiles wall, cpu;
  Percentiles floor;  // identical work of the same median length (fixed_work)
  double contacts_per_tick = 0.0, mean_force = 0.0, max_depth = 0.0;
  int failed = 0;
};

/// One unit of fixed work: a chain of square roots over a small array (in
/// cache), `rounds` passes. The same instructions every call.
double fixed_work(int rounds) {
  static std::vector<double> data(2048, 1.0);
  double s = 0.0;
  for (int r = 0; r < rounds; ++r)
    for (const double x : data) s += std::sqrt(x + 1e-9 * s);
  return s;
}

/// The tail this machine adds to identical work: `count` calls of
/// fixed_work sized to take about `target_us` each (thread CPU time). A
/// tick's p99.9 over its p50 can hardly beat this ratio.
Percentiles fixed_work_floor(int count, double target_us) {
  double sink = fixed_work(1);  // the array made before any timing
  const double t0 = thread_cpu_us();
  sink += fixed_work(16);
  const double per_round = std::max((thread_cpu_us() - t0) / 16.0, 1e-3);
  const int rounds = std::max(1, static_cast<int>(target_us / per_round));
  std::vector<double> us;
  us.reserve(static_cast<std::size_t>(count));
  for (int k = 0; k < count; ++k) {
    const double start = thread_cpu_us();
    sink += fixed_work(rounds);
    us.push_back(thread_cpu_us() - start);
  }
  if (sink == 42.0) std::printf(" ");  // keeps the work from being optimised away
  return percentiles(us);
}

}  // namespace

void tick_section(const std::vector<TickCase>& cases, int ticks, int repeats) {
  const Material clay = *material_preset("clay");
  std::vector<CaseSummary> summaries;
  for (const TickCase& c : cases) {
    std::vector<Percentiles> wall, cpu;
    CaseSummary s;
    s.name = c.name;
    for (int run = 0; run < repeats; ++run) {
      Result<HapticWorld> world = make_world(c.face, clay, c.stroke);
      if (!world.ok()) {
        std::printf("%-36s not run: %s\n", c.name.c_str(), world.status().message.c_str());
        break;
      }
      // Local solves: the ticks that factorised part of a growing window while
      // solving the current one, those that solved the whole net, and the
      // dearest of each (CPU).
      const DeformableBody& body = *world.value().deformable(0);
      const PoleWindow net{0, body.surface().count(Direction::u), 0,
                           body.surface().count(Direction::v)};
      std::vector<char> growing, whole;
      const TickLog log = run_ticks(
          world.value(), [&](int t) { return drag_device(c.face, c.stroke, t); }, ticks,
          [&](int) {
            growing.push_back(body.window_growing() ? 1 : 0);
            whole.push_back(body.solved_window() == net ? 1 : 0);
          });
      double worst_growing = 0.0, worst_whole = 0.0;
      int growing_ticks = 0, whole_ticks = 0;
      for (std::size_t t = 0; t < log.cpu_us.size(); ++t) {
        // A tick worked on a window if one was pending after it or before it.
        const bool grew = growing[t] != 0 || (t > 0 && growing[t - 1] != 0);
        if (grew && whole[t] == 0)
          worst_growing = std::max(worst_growing, log.cpu_us[t]), ++growing_ticks;
        if (whole[t] != 0) worst_whole = std::max(worst_whole, log.cpu_us[t]), ++whole_ticks;
      }
      const Percentiles w = percentiles(log.wall_us), p = percentiles(log.cpu_us);
      wall.push_back(w);
      cpu.push_back(p);
      s.contacts_per_tick = static_cast<double>(log.contacts) / ticks;
      s.mean_force = log.force_sum / ticks;
      s.max_depth = log.max_depth;
      s.failed = log.failed;
      std::printf(
          "%-36s run %d ticks %6d wall: p50 %7.1f p99 %7.1f p99.9 %7.1f max %8.1f us |"
          " cpu: p50 %7.1f p99 %7.1f p99.9 %7.1f max %8.1f us |"
          " contacts/tick %4.1f mean |F| %.3g N max depth %.3g mm |"
          " growing window: %d ticks, max %.1f us; whole net: %d ticks, max %.1f us |"
          " tool queries/tick: contact %.2f (max %d), crossing %.2f (max %d)%s%s\n",
          c.name.c_str(), run + 1, ticks, w.p50, w.p99, w.p999, w.max, p.p50, p.p99, p.p999, p.max,
          s.contacts_per_tick, s.mean_force, s.max_depth, growing_ticks, worst_growing, whole_ticks,
          worst_whole, static_cast<double>(log.contact_queries) / ticks, log.most_contact_queries,
          static_cast<double>(log.crossing_tests) / ticks, log.most_crossing_tests,
          log.failed > 0 ? " | failed ticks: " : "",
          log.failed > 0 ? (std::to_string(log.failed) + " (" + log.first_error + ")").c_str()
                         : "");
      std::fflush(stdout);
    }
    if (cpu.empty()) continue;
    s.wall = median_of(wall);
    s.cpu = median_of(cpu);
    s.floor = fixed_work_floor(ticks, s.cpu.p50);
    std::printf(
        "%-36s identical work of its CPU p50, %d times: p50 %7.1f p99.9 %7.1f max %8.1f us\n",
        c.name.c_str(), ticks, s.floor.p50, s.floor.p999, s.floor.max);
    summaries.push_back(s);
  }

  std::printf("\nPer-tick time, median of %d runs of %d ticks (clay):\n\n", repeats, ticks);
  std::printf(
      "| Case | CPU p50 | CPU p99 | CPU p99.9 | CPU max | wall p50 | wall p99.9 | "
      "contacts/tick | mean F | identical work p99.9 / p50 |\n"
      "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const CaseSummary& s : summaries) {
    std::printf("| %s | %s | %s | %s | %s | %s | %s | %.1f | %.3g N | %.2f |%s\n", s.name.c_str(),
                time_text(s.cpu.p50).c_str(), time_text(s.cpu.p99).c_str(),
                time_text(s.cpu.p999).c_str(), time_text(s.cpu.max).c_str(),
                time_text(s.wall.p50).c_str(), time_text(s.wall.p999).c_str(), s.contacts_per_tick,
                s.mean_force, s.floor.p50 > 0.0 ? s.floor.p999 / s.floor.p50 : 0.0,
                s.failed > 0 ? " (failed ticks)" : "");
  }
  std::fflush(stdout);
}

}  // namespace argil::bench
