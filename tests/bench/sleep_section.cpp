// What untouched bodies cost per tick, with sleep and reach culling on and
// off (docs/benchmarks.md, "Bodies at rest"): a sphere presses and circles on
// a small 8x8 plate while other faces lie 50 mm away.
#include <cmath>
#include <cstdio>

#include "bench_timing.hpp"
#include "haptic_loop_sections.hpp"

namespace argil::bench {

namespace {

/// Faces untouched by the tool: `count` copies of an n x n flat panel (1 mm
/// pitch), in rows of 8 from x = 57 mm (50 mm beyond the pressed plate).
struct Extras {
  std::string name;
  int poles = 0;
  int count = 0;
  bool rigid = false;
};

/// The device: down onto the 7 x 7 mm plate's middle in 50 ticks, then 0.3 mm
/// deep circling 1 mm around it once a second.
Eigen::Vector3d device_at(int t, double radius) {
  const double depth = std::min(1.0, t / 50.0) * 0.3;
  const double a = 2.0 * M_PI * 1e-3 * t;
  return {3.5 + std::cos(a), 3.5 + std::sin(a), radius + 1.0 - std::min(1.0, t / 50.0) - depth};
}

}  // namespace

void sleep_section(int ticks_on, int ticks_off, int repeats) {
  const Material clay = *material_preset("clay");
  const double radius = 2.0;
  const std::vector<Extras> cases = {{"none", 0, 0, false},
                                     {"one 32x32 deformable", 32, 1, false},
                                     {"one 128x128 deformable", 128, 1, false},
                                     {"one 128x128 rigid", 128, 1, true},
                                     {"64 deformable 8x8", 8, 64, false}};
  std::printf(
      "\nBodies at rest: per-tick thread CPU time, median of %d runs of %d ticks (sleep on) and "
      "%d ticks (sleep off):\n\n",
      repeats, ticks_on, ticks_off);
  std::printf("| Extra faces 50 mm away | sleep on p50 | p99.9 | sleep off p50 | p99.9 |\n");
  std::printf("|---|---:|---:|---:|---:|\n");
  for (const Extras& c : cases) {
    Percentiles on_off[2];
    for (const bool sleep : {true, false}) {
      std::vector<Percentiles> runs;
      for (int run = 0; run < repeats; ++run) {
        WorldOptions o;
        o.tolerance = 0.01;
        o.sleep = o.cull = sleep;
        Result<HapticWorld> world = HapticWorld::create(SphereToolShape{radius}, o);
        if (!world.ok()) return;
        HapticWorld& w = world.value();
        if (!w.add_deformable(flat_panel(8, 1.0), clay, {}, 0.3).ok()) return;
        for (int k = 0; k < c.count; ++k) {
          BSplineSurface face = flat_panel(c.poles, 1.0);
          const double pitch = static_cast<double>(c.poles) + 2.0;
          face.control_points.rowwise() +=
              Eigen::RowVector3d(57.0 + pitch * (k % 8), pitch * (k / 8), 0.0);
          const bool added =
              c.rigid ? w.add_rigid(face, 0.3).ok() : w.add_deformable(face, clay, {}, 0.3).ok();
          if (!added) {
            std::printf("| %s | not run: face refused |\n", c.name.c_str());
            return;
          }
        }
        const TickLog log = run_ticks(
            w, [&](int t) { return device_at(t, radius); }, sleep ? ticks_on : ticks_off);
        if (log.failed > 0) std::printf("%s: %d failed ticks\n", c.name.c_str(), log.failed);
        runs.push_back(percentiles(log.cpu_us));
      }
      on_off[sleep ? 0 : 1] = median_of(runs);
    }
    std::printf("| %s | %s | %s | %s | %s |\n", c.name.c_str(), time_text(on_off[0].p50).c_str(),
                time_text(on_off[0].p999).c_str(), time_text(on_off[1].p50).c_str(),
                time_text(on_off[1].p999).c_str());
    std::fflush(stdout);
  }
}

}  // namespace argil::bench
