#pragma once
// Exact refinement of a face where a tool will work (docs/deformation.md,
// Refinement): a face too coarse for the tool (a 2 x 2 plane, a 7 x 2
// cylinder) cannot dent between its control points. Degree elevation gives a
// degree-1 or 2 face interior control points, knot insertion makes the spans
// the tool's region overlaps no longer than the resolution. Neither changes
// the surface or its parametrisation, so trims (in (u, v)) stay valid.

#include <Eigen/Core>
#include <array>
#include <optional>
#include <vector>

#include "argil/core/base/status.hpp"
#include "argil/core/geometry/bspline_surface.hpp"
#include "argil/core/geometry/param_rect.hpp"

namespace argil {

/// Most control points per direction a refinement makes: the tick's cost grows
/// with the net (docs/benchmarks.md), so a finer request is coarsened to fit.
inline constexpr int kMaxRefinedCount = 64;

struct RefinementGoal {
  double resolution = 0.0;  // [mm] longest knot span wanted inside the region
  int min_degree = 3;       // lower degrees are elevated to this
  int max_count = kMaxRefinedCount;
};

/// What a refinement did, for the run summary.
struct RefinementReport {
  std::array<int, 2> degree_before{}, degree_after{};
  std::array<int, 2> count_before{}, count_after{};
  /// The resolution the knot insertion reached [mm]: the goal's, or coarser
  /// when max_count capped it.
  double resolution = 0.0;
  bool capped = false;
  bool changed() const { return degree_before != degree_after || count_before != count_after; }
};

struct Refinement {
  BSplineSurface surface;
  RefinementReport report;
};

/// The box of (u, v) whose surface points lie within `reach` [mm] of the
/// polyline `path` (a single point is a path too): the cells of a sampling
/// grid of the face that may hold such a point, halved where they do until
/// no side is longer than a quarter of the reach; nullopt when no cell may. A
/// cell's points lie within its chord (its longer diagonal) of a corner, and
/// that chord is added to the reach, so a face the path passes within
/// `reach` of is not missed.
std::optional<ParamRect> region_near_path(const BSplineSurface& surface,
                                          const std::vector<Eigen::Vector3d>& path, double reach);

/// `surface` elevated to goal.min_degree and its spans that overlap `region`
/// split evenly into spans at most goal.resolution long (length along the span
/// measured on the surface, the longest iso-line across the region).
/// Precondition: validate(surface).ok(). Errors: resolution not > 0.
Result<Refinement> refine_region(const BSplineSurface& surface, const ParamRect& region,
                                 const RefinementGoal& goal);

}  // namespace argil
