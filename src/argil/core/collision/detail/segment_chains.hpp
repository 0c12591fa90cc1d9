#pragma once
// Chaining of triangle-pair intersection segments into intersection curves
// (the last step of the surface-surface descent before refinement).

#include <Eigen/Core>
#include <array>
#include <vector>

#include "argil/core/collision/contact.hpp"
#include "argil/core/collision/detail/surface_pair_refine.hpp"

namespace argil::detail {

/// One triangle-pair intersection segment with its leaves' parameter sizes.
struct Segment {
  std::array<Eigen::Vector3d, 2> points;
  std::array<Eigen::Vector2d, 2> uv_a, uv_b;
  double width_a, width_b;  // smaller side of each leaf's parameter rectangle
  double reach;             // sum of the leaves' radii [mm]
  /// Its ends already lie on both exact surfaces, refined along the leaves'
  /// edges (a transversal leaf's: see surface_intersection.cpp).
  bool pinned = false;
  /// A pinned segment's curve tangent at each end (from its refinement).
  std::array<CurveTangent, 2> tangents{};
};

/// Curves chained from segments, and per curve point the reach of the segment
/// it came from (how far refinement may move it), whether that segment was
/// pinned and, if so, the curve's tangent there.
struct ChainedCurves {
  std::vector<IntersectionCurve> curves;
  std::vector<std::vector<double>> reaches;
  std::vector<std::vector<bool>> pinned;
  std::vector<std::vector<CurveTangent>> tangents;
};

/// Chains segments into polylines (a segment whose ends both lie within 1e-3
/// eps of another's is a repeat and is left out): end points coincide when they are within
/// eps in space and within half the smaller leaf on each surface in
/// parameters; they are matched greedily, closest pairs first (ties by index,
/// so the result is deterministic). Open chains come first, from their free
/// ends; a closed chain repeats its first point at the end.
ChainedCurves chain_segments(const std::vector<Segment>& segments, double eps);

}  // namespace argil::detail
