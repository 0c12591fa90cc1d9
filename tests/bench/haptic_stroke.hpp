#pragma once
// The scripted device motions of the haptic-loop benchmark and the loop that
// drives a HapticWorld along them, timing every tick alone.

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "argil/core.hpp"
#include "bench_faces.hpp"

namespace argil::bench {

inline constexpr double kTickSeconds = 1e-3;  // [s]
inline constexpr int kDescentTicks = 200;

/// The tool and how it meets a face.
struct StrokeOptions {
  double radius = 5.0;        // sphere radius [mm]
  bool bspline_tool = false;  // the 12 mm bicubic cap instead of the sphere
  double press = 2.0;         // device depth under the rest surface [mm]
  double lift = 10.0;         // height the descent starts from [mm]
  double tolerance = 0.05;    // eps [mm]
  double pass_seconds = 1.0;  // one pass of the drag, u from 0.3 to 0.7 of the domain [s]
  bool vertical = false;      // approach along +z (the panels), else along the outward normal
};

/// Tool-relative sizes for a face of any scale: sphere radius 0.05, press
/// 0.01, lift 0.05 and eps 1e-4 of the face size, one pass of the drag in 1 s.
StrokeOptions scaled_stroke(const BSplineSurface& surface);

/// A world with the stroke's tool (coupling 1 N/mm, 0.002 N s/mm, 8 N max)
/// and the face as one free deformable body of `material`, friction 0.3.
Result<HapticWorld> make_world(const BenchFace& face, const Material& material,
                               const StrokeOptions& stroke);

/// Device position at `tick` of the drag: descend onto (0.3, 0.5) of the
/// domain to `press` under the rest surface, then back and forth along u
/// between 0.3 and 0.7 of the domain.
Eigen::Vector3d drag_device(const BenchFace& face, const StrokeOptions& stroke, int tick);

/// Ticks of the press at one point: descend, hold, rise, relax.
inline constexpr int kHoldTicks = 300;
inline constexpr int kRelaxTicks = 300;
inline constexpr int kPressTicks = 2 * kDescentTicks + kHoldTicks + kRelaxTicks;
/// The tick the hold ends (the device at its deepest since kDescentTicks).
inline constexpr int kHoldEndTick = kDescentTicks + kHoldTicks;

/// Device position at `tick` of a press at (u, v) given as fractions of the
/// domain: descend to `press`, hold, rise back to `lift`, stay there.
Eigen::Vector3d press_device(const BenchFace& face, const StrokeOptions& stroke, double u_fraction,
                             double v_fraction, int tick);

/// What a run of ticks measured.
struct TickLog {
  std::vector<double> wall_us, cpu_us;  // per tick
  long contacts = 0;
  double force_sum = 0.0;   // sum of |F| on the device [N]
  double peak_force = 0.0;  // [N]
  double max_depth = 0.0;   // [mm]
  // The B-spline tool's collision queries (TickResult): in all, and the most in one tick.
  long contact_queries = 0, crossing_tests = 0;
  int most_contact_queries = 0, most_crossing_tests = 0;
  int failed = 0;  // ticks whose status was not ok
  std::string first_error;
};

/// Runs `ticks` ticks with the device at `device(tick)`, timing each alone
/// (wall and thread CPU time). `after(tick)`, if given, runs untimed after
/// each tick. First it keeps the heap resident, as `argil sculpt` does.
TickLog run_ticks(HapticWorld& world, const std::function<Eigen::Vector3d(int)>& device, int ticks,
                  const std::function<void(int)>& after = {});

}  // namespace argil::bench
