#pragma once
// The last step of a surface-surface query: chained (and refined) curves made
// whole. Leaves of different sizes meet at T-junctions where neighbouring
// leaf segments do not share end points, and a curve through a leaf corner or
// along a triangle diagonal leaves short duplicate pieces on the curve.

#include <vector>

#include "argil/core/collision/contact.hpp"

namespace argil::detail {

/// First leaves out points that repeat their predecessor within a millionth of
/// eps (where chained segments of no length met): they would give a curve's
/// end a direction made of rounding. Then drops, shortest first, every curve
/// no longer than eps whose points and chords (checked every eps/4) lie within
/// eps/2 of other curves, and keeps those (a duplicate piece: every point of it
/// stays within eps of the reported set). Then joins open curves
/// whose free ends lie within eps of each other and run on with a turn of at
/// most a right angle, and closes an open curve longer than 2 eps whose own
/// ends meet that way (a closed curve repeats its first point). Isolated short
/// curves are kept.
std::vector<IntersectionCurve> tidy_curves(std::vector<IntersectionCurve> curves, double eps);

}  // namespace argil::detail
