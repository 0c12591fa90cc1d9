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

/// The refined points that continue a curve past its free end `end`, which
/// it leaves along `outward`, up to where the curve ends (a face's edge) or
/// `stop` accepts a chord from one point to the next (another piece reached);
/// empty when it does not go on.
using EndMarch = std::function<IntersectionCurve(
    const CurvePoint& end, const Eigen::Vector3d& outward,
    const std::function<bool(const Eigen::Vector3d& from, const Eigen::Vector3d& to)>& stop)>;

/// How far apart two free ends may lie for tidy_curves() to ask the bridge,
/// in eps: pieces of one curve meet up to about 1.6 eps apart where leaves of
/// different sizes meet, as each piece's end is refined where its own flat
/// leaf crossed the boundary.
inline constexpr double kBridgeReach = 16.0;

/// How far the bridge may reach from each end of a curve [mm], beyond
/// kBridgeReach eps: about the size of the leaves the end's segment came
/// from. A curve that runs along a leaf edge (a crossing along a knot line of
/// both surfaces) passes through the cracks between leaves of different sizes
/// there, and no triangle pair finds it along up to a leaf's edge; along an
/// edge two faces share, the leaves' triangles touch rather than cross, and
/// their segments are scattered pieces of the edge.
/// An end from a transversal leaf (`pinned`) keeps its leaf's reach, but joins
/// through it only the nearest end that faces it: a large leaf's reach could
/// otherwise join two pieces across a third between them.
struct EndReaches {
  double front = 0.0, back = 0.0;
  bool front_pinned = false, back_pinned = false;
};

/// First leaves out points that repeat their predecessor within a millionth of
/// eps (where chained segments of no length met): they would give a curve's
/// end a direction made of rounding. A closed curve that runs out along a
/// stretch and back along it becomes the open curve out, and an open curve
/// that starts or ends out and back over itself starts at its turn (the points
/// left out lie within eps/2 of the rest). Then drops, shortest first, every curve
/// no longer than eps whose points and chords (checked every eps/4) lie within
/// eps/2 of other curves (a duplicate piece: every point of it stays within
/// eps of the reported set, see the last step). Then joins open curves
/// whose free ends lie within eps of each other and run on with a turn of at
/// most a right angle, or that overlap with each end on the other (the
/// overlap left out of one), and closes an open curve longer than 2 eps whose own
/// ends meet that way (a closed curve repeats its first point).
/// With a `bridge`, then joins (and closes) ends that face each other up to
/// kBridgeReach eps apart, or as far as the larger of their `reaches` (one per
/// curve, or none), through the bridge's points; where two pieces
/// overlap by up to kBridgeReach eps, each past the other's end (their refined ends
/// slid along the curve), the overlapping points of one go first.
/// With a `march`, then marches every free end of a curve longer than eps on
/// (stopping within eps of another curve, or of its own away from the end)
/// and joins and closes as before.
/// Then drops every curve still no longer than eps: the surfaces meet there
/// only within eps (faces that touch edge to edge, a loop less than eps/2
/// across), which the query reports as its leaf pair's contact of depth 0.
/// Last drops curves of any length that others cover within eps/2 (as above);
/// one that covered a dropped piece, in this pass or the first, goes only if
/// that piece stays within 3/4 eps of the curves kept (which then stay).
std::vector<IntersectionCurve> tidy_curves(std::vector<IntersectionCurve> curves, double eps,
                                           const GapBridge& bridge = {},
                                           std::vector<EndReaches> reaches = {},
                                           const EndMarch& march = {});

}  // namespace argil::detail
