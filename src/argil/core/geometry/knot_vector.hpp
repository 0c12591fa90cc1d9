#pragma once
// The one check of a degree and knot vector, shared by surfaces (each
// direction) and curves (trim curves included).

#include <Eigen/Core>
#include <string_view>

#include "argil/core/geometry/bspline_surface.hpp"

namespace argil {

/// How messages name the two fields: "degree_u" and "knots_u" for a surface's
/// u direction, "degree" and "knots" for a curve.
struct KnotFieldNames {
  std::string_view degree = "degree";
  std::string_view knots = "knots";
};

/// Checks, in this order: degree in [1, kMaxDegree]; at least 2 (degree + 1)
/// knots; every knot finite and at most kMaxKnotMagnitude in magnitude;
/// non-decreasing; clamped (first and last values repeated degree + 1 times);
/// a non-empty domain; interior multiplicity at most the degree; the domain
/// and every non-empty span at least kMinSpanRatio long (relative to the
/// knots' magnitude and to the domain). Knot comparisons are exact. The
/// result's message names the field, the index and the value.
Status validate_knots(int degree, const Eigen::VectorXd& knots, const KnotFieldNames& names = {});

}  // namespace argil
