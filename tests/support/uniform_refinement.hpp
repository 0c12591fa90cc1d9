#pragma once
// Exact uniform refinement of a surface, for resolution-independence tests:
// the same surface on a finer net.

#include "argil/core/geometry/bspline_surface.hpp"

namespace argil::test {

/// `surface` with every non-empty knot span of both directions halved
/// `times` times by exact knot insertion (insert_knot).
BSplineSurface halved_spans(BSplineSurface surface, int times);

}  // namespace argil::test
