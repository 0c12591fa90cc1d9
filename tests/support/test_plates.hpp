#pragma once
// Flat plates made of Bezier-like pieces, for the deformation regression cases:
// degree 1 across, `degree` along v in `pieces` pieces whose joins have knot
// multiplicity `join` (join = degree: C0), poles at the Greville abscissae so
// the plate is S(u, v) = (width u, height v, 0) exactly.

#include <Eigen/Core>

#include "argil/core/geometry/bspline_surface.hpp"

namespace argil::test {

struct PlateShape {
  double width = 1.0;   // along u [mm]
  double height = 1.0;  // along v [mm]
  int spans_u = 1;      // degree 1 spans along u (spans_u + 1 poles)
  int degree_v = 10;
  int pieces_v = 2;
  int join_v = 10;  // multiplicity of the interior knots between pieces
};

/// Clamped knots on [0, 1]: `pieces` equal pieces of `degree`, interior knots
/// repeated `join` times.
Eigen::VectorXd piece_knots(int degree, int pieces, int join);

/// The flat plate of `shape` in z = 0.
BSplineSurface flat_plate(const PlateShape& shape);

/// A flat bicubic `size` x `size` mm panel in z = 0 with `spans` equal knot
/// spans each way, its poles at the Greville abscissae (x = size u exactly).
BSplineSurface flat_bicubic_panel(double size, int spans);

}  // namespace argil::test
