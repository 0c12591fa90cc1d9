#pragma once
// Marching a refined intersection curve on past a free end. The descent finds
// a curve through its leaves' triangles; where two faces meet along an edge
// the triangles touch rather than cross, their segments are scattered, and
// the pieces can stop short of where the curve really ends (the edge's end).

#include <Eigen/Core>
#include <functional>

#include "argil/core/collision/contact.hpp"
#include "argil/core/collision/detail/surface_pair_refine.hpp"

namespace argil {

/// True when the marched chord from `from` to `to` comes near another piece.
using ChordStop = std::function<bool(const Eigen::Vector3d& from, const Eigen::Vector3d& to)>;

/// The refined points that continue a curve past its free end `end` (a point
/// on both surfaces), leaving along `outward`, every chord within `tolerance`
/// of the curve (CurveDensifier). Steps along the curve's tangent n_a x n_b
/// (a parameter on its domain edge stays on it where the curve runs along the
/// edge), refines each step across the curve, and doubles the step while no
/// point is needed between steps or halves it, down to the tolerance, where a
/// step does not refine ahead. Stops where the curve leaves either domain,
/// where it no longer refines (a tangency, or no curve beyond the end), at the
/// end of the first chord that `stop` accepts (it comes near another piece),
/// and at 1e4 points. Empty when the curve does not go on, or `outward` has
/// no direction.
IntersectionCurve march_from_end(const SurfacePair& pair, const PairPoint& end,
                                 const Eigen::Vector3d& outward, double tolerance,
                                 const ChordStop& stop);

}  // namespace argil
