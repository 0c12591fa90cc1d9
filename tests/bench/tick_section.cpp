// Per-tick time of the press-and-drag stroke (docs/benchmarks.md, "Full haptic tick").
#include <algorithm>
#include <cstdio>

#include "bench_timing.hpp"
#include "haptic_loop_sections.hpp"

namespace argil::bench {

namespace {

struct CaseSummary {
  std::string name;
  Percentiles wall, cpu;
  double contacts_per_tick = 0.0, mean_force = 0.0, max_depth = 0.0;
  int failed = 0;
};

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
          " growing window: %d ticks, max %.1f us; whole net: %d ticks, max %.1f us%s%s\n",
          c.name.c_str(), run + 1, ticks, w.p50, w.p99, w.p999, w.max, p.p50, p.p99, p.p999, p.max,
          s.contacts_per_tick, s.mean_force, s.max_depth, growing_ticks, worst_growing, whole_ticks,
          worst_whole, log.failed > 0 ? " | failed ticks: " : "",
          log.failed > 0 ? (std::to_string(log.failed) + " (" + log.first_error + ")").c_str()
                         : "");
      std::fflush(stdout);
    }
    if (cpu.empty()) continue;
    s.wall = median_of(wall);
    s.cpu = median_of(cpu);
    summaries.push_back(s);
  }

  std::printf("\nPer-tick time, median of %d runs of %d ticks (clay):\n\n", repeats, ticks);
  std::printf(
      "| Case | CPU p50 | CPU p99 | CPU p99.9 | CPU max | wall p50 | wall p99.9 | "
      "contacts/tick | mean F |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const CaseSummary& s : summaries) {
    std::printf("| %s | %s | %s | %s | %s | %s | %s | %.1f | %.3g N |%s\n", s.name.c_str(),
                time_text(s.cpu.p50).c_str(), time_text(s.cpu.p99).c_str(),
                time_text(s.cpu.p999).c_str(), time_text(s.cpu.max).c_str(),
                time_text(s.wall.p50).c_str(), time_text(s.wall.p999).c_str(), s.contacts_per_tick,
                s.mean_force, s.failed > 0 ? " (failed ticks)" : "");
  }
  std::fflush(stdout);
}

}  // namespace argil::bench
