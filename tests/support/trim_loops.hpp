#pragma once
// Trim loops for tests: lines, exact rational arcs and ellipses, wavy
// B-spline curves, and an asymmetric set of loops over a surface's domain.

#include <Eigen/Core>
#include <vector>

#include "argil/core/geometry/bspline_surface.hpp"
#include "argil/core/geometry/trim_region.hpp"

namespace argil::test {

/// The straight trim curve from a to b (degree 1).
BSplineCurve trim_line(const Eigen::Vector2d& a, const Eigen::Vector2d& b);

/// The exact elliptic arc centre + (rx cos a, ry sin a) for a from a0 to a1
/// (|a1 - a0| <= pi / 2): a rational quadratic Bezier.
BSplineCurve trim_arc(const Eigen::Vector2d& centre, double rx, double ry, double a0, double a1);

/// A closed ellipse of four exact arcs: counter-clockwise, or clockwise for
/// a hole (outer = false).
TrimLoop ellipse_loop(const Eigen::Vector2d& centre, double rx, double ry, bool outer);

/// A closed rectangle of four lines, counter-clockwise, or clockwise for a hole.
TrimLoop rectangle_loop(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, bool outer);

/// Loops over `domain` with every kind of piece: an outer loop of a wavy
/// cubic with non-uniform knots and a double knot, an exact rational arc, a
/// line and a wavy degree-4 rational curve, with a gap of 1e-5 of the domain
/// between two curves; an elliptic hole and a rectangular hole.
std::vector<TrimLoop> asymmetric_trims(const ParamRect& domain);

/// Where the loop runs: every curve sampled at `per_curve` points (gap segments
/// between curves are the polygon's closing edges).
std::vector<Eigen::Vector2d> dense_polygon(const TrimLoop& loop, int per_curve);

/// Even-odd rule on polygons: the oracle for points far from their edges.
bool inside_polygons(const std::vector<std::vector<Eigen::Vector2d>>& polygons,
                     const Eigen::Vector2d& uv);

/// Distance from uv to the nearest polygon edge.
double polygon_distance(const std::vector<std::vector<Eigen::Vector2d>>& polygons,
                        const Eigen::Vector2d& uv);

/// A surface of degree 3 x 2 with 7 x 5 poles (non-uniform knots in v) over
/// [0, 1] x [0, 1], whose poles sit at the Greville abscissae scaled by `size`
/// [mm], so x = size u and y = size v exactly (linear precision) and z =
/// `height` [mm]: a u/v-asymmetric net for a flat plate with an exact (u, v)
/// to (x, y) map.
BSplineSurface asymmetric_plate(double size, double height);

}  // namespace argil::test
