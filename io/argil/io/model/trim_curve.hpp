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

/// A closed polygon through the loop in (u, v): every curve sampled at
/// `samples_per_span` points per non-empty knot span (curved spans are sampled
/// evenly in t; lines need only their ends). The first point is not repeated.
std::vector<Eigen::Vector2d> loop_polygon(const TrimLoop& loop, int samples_per_span = 16);

/// Even-odd rule over all loops of a face: true when (u, v) is inside the outer
/// loop and outside every inner loop. Points exactly on a polygon edge may fall
/// either way.
bool inside_trim(const std::vector<std::vector<Eigen::Vector2d>>& polygons,
                 const Eigen::Vector2d& uv);

/// Checks the surface and every trim curve of a face; the message names the
/// loop and curve and the defect ("loop 0 curve 2: ..."), not the face, for
/// callers that name the face themselves.
Status validate_face(const FaceRecord& face);

/// validate_face(face) with the message prefixed by the face index
/// ("face 3 loop 0 curve 2: ...").
Status validate_face(const FaceRecord& face, std::size_t face_index);

}  // namespace argil::io
