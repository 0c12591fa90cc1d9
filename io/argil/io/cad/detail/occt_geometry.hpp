#pragma once
// Internal to argil_io: argil's B-splines as OpenCASCADE geometry, for export.

#include <Geom2d_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>

#include "argil/core/geometry/bspline_curve.hpp"
#include "argil/core/geometry/bspline_surface.hpp"

namespace argil::io::detail {

/// The writers' float format ("%#.17G") fills a 24-byte buffer: a number below
/// 1e-99 needs a three-digit exponent and would overflow it. Such numbers are 0.
double writable(double x);

/// The same surface (knots, weights, poles bit for bit, up to writable()).
Handle(Geom_BSplineSurface) to_occt(const BSplineSurface& surface);

/// The same planar curve, its two columns as (u, v).
Handle(Geom2d_BSplineCurve) to_occt(const BSplineCurve& curve);

}  // namespace argil::io::detail
