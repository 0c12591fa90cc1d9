#pragma once
// The last step of a surface-surface query: chained (and refined) curves made
// whole. Leaves of different sizes meet at T-junctions where neighbouring
// leaf segments do not share end points, and a curve through a leaf corner or
// along a triangle diagonal leaves short duplicate pieces on the curve.

#include <functional>
#include <optional>
#include <vector>

#include "argil/core/collision/contact.hpp"

namespace argil::detail {

/// One point of an intersection curve with its parameters on both surfaces.
struct CurvePoint {
  Eigen::Vector3d point;
  Eigen::Vector2d uv_a, uv_b;
};

/// The points strictly between two free curve ends that lie more than eps
/// apart, in order from `from` to `to`, on both surfaces with every chord
/// within eps/3 of the curve; nullopt when no single branch of the curve runs
/// from one end to the other.
using GapBridge =
    std::function<std::optional<IntersectionCurve>(const CurvePoint& from, const CurvePoint& to)>;

/// How far apart two free ends may lie for tidy_curves() to ask the bridge,
/// in eps: pieces of one curve meet up to about 1.6 eps apart where leaves of
/// different sizes meet, as each piece's end is refined where its own flat
/// leaf crossed the boundary.
inline constexpr double kBridgeReach = 16.0;

/// First leaves out points that repeat their predecessor within a millionth of
/// eps (where chained segments of no length met): they would give a curve's
/// end a direction made of rounding; a closed curve of three points, out to one
/// point and back, becomes the open curve out. Then drops, shortest first, every curve
/// no longer than eps whose points and chords (checked every eps/4) lie within
/// eps/2 of other curves, and keeps those (a duplicate piece: every point of it
/// stays within eps of the reported set). Then joins open curves
/// whose free ends lie within eps of each other and run on with a turn of at
/// most a right angle, and closes an open curve longer than 2 eps whose own
/// ends meet that way (a closed curve repeats its first point).
/// With a `bridge`, then joins (and closes) ends up to kBridgeReach eps apart
/// that face each other, through the bridge's points; where two pieces
/// overlap by up to as much, each past the other's end (their refined ends
/// slid along the curve), the overlapping points of one go first.
/// Last drops every curve still no longer than eps: the surfaces meet there
/// only within eps (faces that touch edge to edge, a loop less than eps/2
/// across), which the query reports as its leaf pair's contact of depth 0.
std::vector<IntersectionCurve> tidy_curves(std::vector<IntersectionCurve> curves, double eps,
                                           const GapBridge& bridge = {});

}  // namespace argil::detail
