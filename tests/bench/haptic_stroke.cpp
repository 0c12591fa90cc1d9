#include "haptic_stroke.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "bench_surfaces.hpp"
#include "bench_timing.hpp"
#include "support/tool_shapes.hpp"

namespace argil::bench {

namespace {

double domain_at(const BSplineSurface& s, Direction d, double fraction) {
  return s.domain_start(d) + fraction * (s.domain_end(d) - s.domain_start(d));
}

/// Where the tool's reference point is when the device's contact point is
/// `height` above the rest surface at (u, v) given as domain fractions: the
/// sphere's centre is a radius further out; the cap's origin is its lowest point.
Eigen::Vector3d device_over(const BenchFace& face, const StrokeOptions& stroke, double u_fraction,
                            double v_fraction, double height) {
  const BSplineSurface& s = face.surface;
  const double u = domain_at(s, Direction::u, u_fraction);
  const double v = domain_at(s, Direction::v, v_fraction);
  const Eigen::Vector3d point = evaluate_derivatives(s, u, v, 0).point;
  const Eigen::Vector3d out =
      stroke.vertical ? Eigen::Vector3d(Eigen::Vector3d::UnitZ())
                      : Eigen::Vector3d((face.reversed ? -1.0 : 1.0) * unit_normal(s, u, v));
  const double offset = stroke.bspline_tool ? 0.0 : stroke.radius;
  return point + out * (offset + height);
}

}  // namespace

StrokeOptions scaled_stroke(const BSplineSurface& surface) {
  const double size = face_size(surface);
  return {.radius = 0.05 * size,
          .bspline_tool = false,
          .press = 0.01 * size,
          .lift = 0.05 * size,
          .tolerance = 1e-4 * size,
          .pass_seconds = 1.0,
          .vertical = false};
}

Result<HapticWorld> make_world(const BenchFace& face, const Material& material,
                               const StrokeOptions& stroke) {
  WorldOptions options;
  options.tolerance = stroke.tolerance;
  options.coupling = {.stiffness = 1.0, .damping = 0.002, .max_force = 8.0};
  const ToolShape tool = stroke.bspline_tool ? ToolShape{SurfaceToolShape{test::bowl_cap()}}
                                             : ToolShape{SphereToolShape{stroke.radius}};
  Result<HapticWorld> world = HapticWorld::create(tool, options);
  if (!world.ok()) return world;
  const Result<int> body = world.value().add_deformable(face.surface, material, {}, 0.3);
  if (!body.ok()) return body.status();
  return world;
}

Eigen::Vector3d drag_device(const BenchFace& face, const StrokeOptions& stroke, int tick) {
  const double descend = std::max(0.0, 1.0 - static_cast<double>(tick) / kDescentTicks);
  const double seconds = kTickSeconds * std::max(0, tick - kDescentTicks);
  const double phase = std::fmod(seconds / stroke.pass_seconds, 2.0);  // a pass and back
  const double along = phase < 1.0 ? phase : 2.0 - phase;
  const double height = -stroke.press + (stroke.lift + stroke.press) * descend;
  return device_over(face, stroke, 0.3 + 0.4 * along, 0.5, height);
}

Eigen::Vector3d press_device(const BenchFace& face, const StrokeOptions& stroke, double u_fraction,
                             double v_fraction, int tick) {
  const double travel = stroke.lift + stroke.press;
  double height = stroke.lift;
  if (tick < kDescentTicks) {
    height = stroke.lift - travel * tick / kDescentTicks;
  } else if (tick < kHoldEndTick) {
    height = -stroke.press;
  } else if (tick < kHoldEndTick + kDescentTicks) {
    height = -stroke.press + travel * (tick - kHoldEndTick) / kDescentTicks;
  }
  return device_over(face, stroke, u_fraction, v_fraction, height);
}

TickLog run_ticks(HapticWorld& world, const std::function<Eigen::Vector3d(int)>& device, int ticks,
                  const std::function<void(int)>& after) {
  // As `argil sculpt` does before its ticks: a tick reuses heap pages instead
  // of faulting in fresh ones (the first run's tail otherwise).
  keep_heap_resident(kHapticHeapReserve);
  TickLog log;
  log.wall_us.reserve(static_cast<std::size_t>(ticks));
  log.cpu_us.reserve(static_cast<std::size_t>(ticks));
  for (int t = 0; t < ticks; ++t) {
    const DeviceSample sample{
        .tick = t, .t = t * kTickSeconds, .X_WD = Pose::at(device(t)), .engaged = true};
    const double cpu_start = thread_cpu_us();
    const auto start = std::chrono::steady_clock::now();
    const TickResult r = world.step(sample, kTickSeconds);
    const auto stop = std::chrono::steady_clock::now();
    log.cpu_us.push_back(thread_cpu_us() - cpu_start);
    log.wall_us.push_back(std::chrono::duration<double, std::micro>(stop - start).count());
    log.contact_queries += r.tool_contact_queries;
    log.crossing_tests += r.tool_crossing_tests;
    log.most_contact_queries = std::max(log.most_contact_queries, r.tool_contact_queries);
    log.most_crossing_tests = std::max(log.most_crossing_tests, r.tool_crossing_tests);
    if (r.status.ok()) {
      log.contacts += r.contacts;
      log.max_depth = std::max(log.max_depth, r.max_depth);
      log.force_sum += r.force.norm();
      log.peak_force = std::max(log.peak_force, r.force.norm());
    } else if (log.failed++ == 0) {
      log.first_error = r.status.message;
    }
    if (after) after(t);
  }
  return log;
}

}  // namespace argil::bench
