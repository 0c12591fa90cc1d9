#pragma once
// Checks and evaluation of trim curves and loops in (u, v) parameter space.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "argil/core/base/status.hpp"
#include "argil/io/model/model.hpp"

namespace argil::io {

/// Checks a trim curve: two columns of points, then every invariant of
/// BSplineCurve with the rules surfaces follow (validate(const BSplineCurve&)).
/// The message starts "trim curve: " and names the first problem's field,
/// index and value.
Status validate_trim_curve(const TrimCurve& curve);

/// Point of the curve at t (clamped to the knot range). Precondition:
/// validate_trim_curve(curve).ok(). The NURBS Book A4.1.
Eigen::Vector2d evaluate_trim_curve(const TrimCurve& curve, double t);

/// Checks the surface and every trim curve of a face; the message names the
/// loop and curve and the defect ("loop 0 curve 2: ..."), not the face, for
/// callers that name the face themselves. It does not check how the curves
/// chain: a model holds whatever finite loops a file gave. Code that needs
/// the region (tessellation, the physics) builds argil::TrimRegion from the
/// loops, which checks that they close, enclose an area and run the right
/// way round (argil::validate_trim_loops), then asks contains().
Status validate_face(const FaceRecord& face);

/// validate_face(face) with the message prefixed by the face index
/// ("face 3 loop 0 curve 2: ...").
Status validate_face(const FaceRecord& face, std::size_t face_index);

}  // namespace argil::io
