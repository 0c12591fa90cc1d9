#pragma once
// The rows of poles across a face's C0 knot lines (docs/deformation.md,
// Joins). On a C0 line of a direction of degree >= 2, pole `on` lies on the
// line and `before`, `after` are its neighbours either side: the surface's
// cross-line tangents there are along on - before and after - on. Where the
// rest row is straight (a G1 join), the step ties the displacement of `on`
// to its neighbours', d_on = lambda d_before + (1 - lambda) d_after, so the
// row stays straight with its rest proportions under any load: the join stays
// G1 exactly, with no stiff penalty. A crease is not tied (rotating it
// rigidly would violate the tie); the joint term of the shell energy holds
// its angle.

#include <array>
#include <vector>

#include "argil/core/geometry/bspline_surface.hpp"
#include "argil/core/linalg/banded_cholesky.hpp"

namespace argil {

/// A rest row whose legs turn by less than this [rad] is a G1 join and is
/// tied; a sharper one is a crease.
inline constexpr double kG1JoinAngle = 1e-3;

struct JoinRow {
  int before = 0, on = 0, after = 0;  // pole indices
  /// |P_after - P_on| / |P_on - P_before| at rest.
  double ratio = 0.0;
  /// A G1 join: the step ties d_on = lambda() d_before + (1 - lambda()) d_after.
  bool tied = false;
  /// 0 when the line is a line u = const (rows along u), 1 for v = const.
  int direction = 0;
  double lambda() const { return ratio / (1.0 + ratio); }
};

/// Every row across every C0 knot line of a direction of degree >= 2 (a
/// degree-1 direction's lines are its facets' folds), skipping rows with a
/// held pole (`held`, one flag per pole) or a zero-length leg.
std::vector<JoinRow> join_rows(const BSplineSurface& rest, const std::vector<char>& held);

/// a <- T^T a T, T the tie of every tied row (a in solve order: `rank` maps a
/// pole to its unknown). A tied row's `on` unknown is left decoupled with a
/// unit diagonal. The band must reach two poles further along each tied
/// direction than `a`'s own couplings (tie_reach).
void tie_matrix(SymmetricBandMatrix& a, const std::vector<JoinRow>& rows,
                const std::vector<int>& rank);
/// b <- T^T b (loads onto the unknowns; the `on` rows become zero).
void tie_load(RowMajorMatrix& b, const std::vector<JoinRow>& rows, const std::vector<int>& rank);
/// x <- T x (the solved unknowns back onto every pole).
void untie_solution(RowMajorMatrix& x, const std::vector<JoinRow>& rows,
                    const std::vector<int>& rank);

/// How many more poles the couplings reach along u and v once tied: 2 in a
/// direction with a tied row (each end of a coupling may move one pole), else 0.
std::array<int, 2> tie_reach(const std::vector<JoinRow>& rows);

}  // namespace argil
