#pragma once
// Internal to argil_io: an edge's parameter-space curve on a face as argil's
// clamped B-spline, shared by the face reader (trim loops) and the topology
// reader (edge uses).

#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>

#include "argil/core/base/status.hpp"
#include "argil/core/geometry/bspline_curve.hpp"

namespace argil::io::detail {

/// Which way a pcurve runs: as the edge (`edge`: its orientation only selects
/// which of a seam edge's two pcurves is meant) or as the edge runs in its
/// wire (`wire`: reversed for a REVERSED edge, so a loop chains head to tail).
enum class PcurveDirection { edge, wire };

/// The pcurve of `edge` on `face` over the edge's range, as a clamped
/// non-periodic B-spline with the same parameters where OpenCASCADE keeps them
/// (B-splines and lines; conics become rational B-splines).
/// Error: the edge has no pcurve on the face.
Result<BSplineCurve> edge_pcurve(const TopoDS_Edge& edge, const TopoDS_Face& face,
                                 PcurveDirection direction);

}  // namespace argil::io::detail
