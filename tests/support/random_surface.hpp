#pragma once
// Generated surfaces for property and oracle tests.

#include <random>

#include "argil/core/geometry/bspline_surface.hpp"

namespace argil::test {

/// What random_surface() draws.
struct RandomSurfaceOptions {
  int min_degree = 1;
  int max_degree = 5;
  int max_extra_poles = 6;  // count = degree + 1 + uniform[0, max_extra_poles]
  bool rational = false;
  double min_weight = 0.3;  // weights uniform in [min_weight, max_weight]
  double max_weight = 3.0;
  bool repeated_knots = true;  // some interior knots get multiplicity up to degree
  double size = 100.0;         // control points within a box this wide [mm]
};

/// A valid surface with random non-uniform clamped knots (domain not [0, 1]),
/// repeated interior knots, a wavy control net and optional random weights.
BSplineSurface random_surface(std::mt19937_64& rng, const RandomSurfaceOptions& options = {});

/// The asymmetric test surface (docs/conventions.md, Testing): degree 3x2, 7x5
/// control points, non-uniform knots, one double interior knot in u, non-unit
/// weights when `rational`.
BSplineSurface asymmetric_surface(bool rational = true);

}  // namespace argil::test
