#pragma once
// The three parts of bench_haptic_loop (docs/benchmarks.md), each printing
// its runs and a summary table.

#include <functional>
#include <string>
#include <vector>

#include "bench_faces.hpp"
#include "haptic_stroke.hpp"

namespace argil::bench {

/// One timed case: a face, a tool and its stroke.
struct TickCase {
  std::string name;
  BenchFace face;
  StrokeOptions stroke;
};

/// Per-tick wall and thread CPU time of the press-and-drag stroke, `repeats`
/// runs of `ticks` ticks per case with the clay preset; each percentile is the
/// median over the runs.
void tick_section(const std::vector<TickCase>& cases, int ticks, int repeats);

/// One face of the refinement table, pressed at (u, v) (domain fractions).
struct RefinementCase {
  std::string name;
  BenchFace face;
  double u_fraction = 0.5, v_fraction = 0.5;
};

/// Dent depth and peak force of the same press on refinement levels 0, 1 and
/// 2 (midpoint knot insertion), with the foam and clay presets.
void refinement_section(const std::vector<RefinementCase>& cases);

/// Creation cost of a deformable body (shell matrices, create, first step
/// with the factorisation), medians over `repeats` runs of a few creations.
void creation_section(const std::vector<BenchFace>& faces, int repeats);

/// Per-tick CPU time of a sphere pressing a small plate while other faces
/// (deformable or rigid) lie untouched 50 mm away, with WorldOptions::sleep
/// and cull on and off, `repeats` runs of `ticks_on` and `ticks_off` ticks (a
/// 128x128 face awake costs ~30 ms a tick: fewer ticks with sleep off).
void sleep_section(int ticks_on, int ticks_off, int repeats);

/// The one-off cost of refining every face of each file (tests/data) over
/// its whole domain for a tool whose radius is `size_fraction` of the part's
/// size (refine_region; region_near_path timed on a path through each face's
/// middle): per file the faces refined, poles before and after, and CPU time.
void tool_refinement_section(const std::vector<std::string>& files, double size_fraction);

/// A scene of the size table: its faces, made in the row's own process,
/// which sets `pressed` to the face the sphere presses at its domain's middle.
/// The sphere is 2 mm (press 0.3 mm, eps 0.01 mm) on the generated 2 mm
/// pitch panels, or sized to the pressed face (`scaled`: scaled_stroke).
struct ScaleCase {
  std::string name;
  std::function<std::vector<BenchFace>(int& pressed)> faces;
  bool scaled = false;
};

/// Per-tick CPU time of a sphere pressing and circling on one spot against
/// what the scene holds, each row in a child process (peak memory, and a
/// row over `row_seconds` is reported as stopped): creation time, p50, p99,
/// p99.9, worst tick and peak memory, plus a `scale-csv` line per row.
void scale_section(const std::vector<ScaleCase>& cases, int ticks, int repeats, int row_seconds);

}  // namespace argil::bench
