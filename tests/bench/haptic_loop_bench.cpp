// The full haptic tick (docs/benchmarks.md): collide, contact and friction forces,
// implicit deformation, exact refit, device force, on 16x16, 32x32 and 64x64
// bicubic panels with a sphere tool and with a B-spline tool, along a scripted
// stroke that presses 2 mm into the panel and drags across it at 100 mm/s.
// Each tick is timed alone (steady_clock); prints p50, p99, p99.9 and max.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

#include "argil/core.hpp"
#include "bench_surfaces.hpp"

namespace {

constexpr double kDt = 1e-3;       // [s]
constexpr double kPress = 2.0;     // device depth under the rest surface [mm]
constexpr double kApproach = 200;  // ticks to descend from 10 mm above

/// A bowl-shaped bicubic cap 12 mm wide, lowest near its frame origin.
argil::BSplineSurface cap_tool() {
  argil::BSplineSurface tool;
  tool.degree = {3, 3};
  tool.knots = {argil::bench::uniform_knots(3, 4), argil::bench::uniform_knots(3, 4)};
  tool.control_points.resize(16, 3);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      const double x = -6.0 + 4.0 * i, y = -6.0 + 4.0 * j;
      tool.control_points.row(tool.pole_index(i, j)) << x, y, 0.05 * (x * x + y * y);
    }
  return tool;
}

/// Device position at tick t: descend onto (u, v) = (0.3, 0.5), then drag
/// along u at 100 mm/s for the rest of the run (a back-and-forth stroke).
Eigen::Vector3d device_at(const argil::BSplineSurface& rest, double tool_offset, int t, int ticks) {
  const double width = rest.control_points.col(0).maxCoeff();
  const double span = 0.4 * width;                           // stroke length [mm]
  const double travel = 0.1 * std::max(0.0, t - kApproach);  // [mm] at 100 mm/s
  const double phase = std::fmod(travel, 2.0 * span);
  const double along = phase < span ? phase : 2.0 * span - phase;
  const double u = 0.3 + 0.4 * along / span;
  (void)ticks;
  const auto d = argil::evaluate_derivatives(rest, u, 0.5, 1);
  const double descend = std::max(0.0, 1.0 - t / kApproach);
  return d.point + Eigen::Vector3d::UnitZ() * (tool_offset - kPress + (10.0 + kPress) * descend);
}

/// CPU time of this thread [us]: unlike wall time, it excludes time the
/// scheduler gave to other processes on a loaded machine.
double thread_cpu_us() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return 1e6 * static_cast<double>(ts.tv_sec) + 1e-3 * static_cast<double>(ts.tv_nsec);
}

struct Percentiles {
  double p50, p99, p999, max;
};

Percentiles percentiles(std::vector<double> us) {
  std::sort(us.begin(), us.end());
  const auto at = [&](double q) {
    return us[std::min(us.size() - 1,
                       static_cast<std::size_t>(q * static_cast<double>(us.size())))];
  };
  return {at(0.5), at(0.99), at(0.999), us.back()};
}

void run(int poles, bool sphere, int ticks) {
  const argil::BSplineSurface panel = argil::bench::bicubic_panel(poles);
  argil::WorldOptions options;
  options.tolerance = 0.05;  // [mm]
  options.coupling = {.stiffness = 1.0, .damping = 0.002, .max_force = 8.0};
  const argil::ToolShape tool = sphere ? argil::ToolShape{argil::SphereToolShape{5.0}}
                                       : argil::ToolShape{argil::SurfaceToolShape{cap_tool()}};
  auto world = argil::HapticWorld::create(tool, options);
  if (!world.ok()) std::abort();
  argil::Material clay;
  clay.density = 2e-5;
  clay.stiffness = 1.0;
  clay.anchor_stiffness = 1.0;
  clay.damping = 1e-3;
  clay.yield = 0.5;
  if (!world.value().add_deformable(panel, clay, {}, /*friction=*/0.3).ok()) std::abort();
  const double offset = sphere ? 5.0 : 0.0;  // sphere centre above its contact point
  std::vector<double> us, cpu;
  us.reserve(static_cast<std::size_t>(ticks));
  cpu.reserve(static_cast<std::size_t>(ticks));
  long contacts = 0;
  double max_depth = 0.0, force = 0.0;
  for (int t = 0; t < ticks; ++t) {
    const argil::DeviceSample device{.tick = t,
                                     .t = t * kDt,
                                     .X_WD = argil::Pose::at(device_at(panel, offset, t, ticks)),
                                     .engaged = true};
    const double cpu_start = thread_cpu_us();
    const auto start = std::chrono::steady_clock::now();
    const argil::TickResult r = world.value().step(device, kDt);
    const auto stop = std::chrono::steady_clock::now();
    cpu.push_back(thread_cpu_us() - cpu_start);
    us.push_back(std::chrono::duration<double, std::micro>(stop - start).count());
    contacts += r.contacts;
    max_depth = std::max(max_depth, r.max_depth);
    force += r.force.norm();
  }
  const Percentiles p = percentiles(us);
  const Percentiles c = percentiles(cpu);
  std::printf(
      "%2dx%-2d %-8s ticks %6d wall: p50 %7.1f p99 %7.1f p99.9 %7.1f max %8.1f us |"
      " cpu: p50 %7.1f p99 %7.1f p99.9 %7.1f max %8.1f us |"
      " contacts/tick %4.1f mean |F| %4.2f N max depth %.4f mm\n",
      poles, poles, sphere ? "sphere" : "bspline", ticks, p.p50, p.p99, p.p999, p.max, c.p50, c.p99,
      c.p999, c.max, static_cast<double>(contacts) / ticks, force / ticks, max_depth);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  // Arguments: [ticks] [poles] [sphere|bspline] to run one case.
  const int ticks = argc > 1 ? std::atoi(argv[1]) : 20000;
  const int only_poles = argc > 2 ? std::atoi(argv[2]) : 0;
  const std::string only_tool = argc > 3 ? argv[3] : "";
  for (const int poles : {16, 32, 64}) {
    if (only_poles != 0 && poles != only_poles) continue;
    if (only_tool != "bspline") run(poles, true, ticks);
    if (only_tool != "sphere") run(poles, false, ticks);
  }
  return 0;
}
