#pragma once
// The u/v transpose of a surface, for tests that must catch a u/v swap bug:
// S^T(v, u) = S(u, v) with the net, degrees, knots and weights swapped.

#include <Eigen/Core>

#include "argil/core/geometry/bspline_surface.hpp"

namespace argil::test {

/// The same surface with u and v swapped: pole (i, j) becomes pole (j, i),
/// degree and knots of u become those of v and back, weights follow their poles.
/// Its normal S^T_u x S^T_v is the negated normal of the original.
BSplineSurface transposed(const BSplineSurface& surface);

/// Rows of a per-pole (or per-node) array of an n_u x n_v grid, row i * n_v + j,
/// reordered for the transposed grid, row j * n_u + i. Any number of columns.
template <typename Matrix>
Matrix transposed_rows(const Matrix& rows, int count_u, int count_v) {
  Matrix out(rows.rows(), rows.cols());
  for (int i = 0; i < count_u; ++i)
    for (int j = 0; j < count_v; ++j)
      out.row(static_cast<Eigen::Index>(j) * count_u + i) =
          rows.row(static_cast<Eigen::Index>(i) * count_v + j);
  return out;
}

}  // namespace argil::test
