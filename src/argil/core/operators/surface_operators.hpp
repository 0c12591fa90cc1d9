#pragma once
// Surface-level use of the per-direction operators: grid evaluation, Bezier
// patches, and the node <-> control point maps at the Greville abscissae.
// All linear in the control points; nothing here is rebuilt when they move.

#include <Eigen/Core>
#include <memory>

#include "argil/core/base/status.hpp"
#include "argil/core/geometry/bezier.hpp"
#include "argil/core/geometry/bspline_surface.hpp"
#include "argil/core/operators/curve_operators.hpp"

namespace argil {

/// The operators of a surface structure: one CurveOperators per direction.
struct SurfaceOperators {
  std::shared_ptr<const CurveOperators> u;
  std::shared_ptr<const CurveOperators> v;
  const CurveOperators& in(Direction d) const { return d == Direction::u ? *u : *v; }
};

/// Validates the surface, then fetches (or builds) its operators from `cache`.
Result<SurfaceOperators> surface_operators(const BSplineSurface& surface, OperatorCache& cache);

/// Samples on a tensor grid; row a * count_v + b holds sample (u_a, v_b).
/// Second derivatives are filled only when evaluated with order 2.
struct SurfaceGrid {
  int count_u = 0;
  int count_v = 0;
  ControlNet points, du, dv, duu, duv, dvv;
  ControlNet normals;  // unit, zero where S_u x S_v vanishes
};

/// Evaluates the grid u_rows x v_rows through the precomputed rows: points,
/// and derivatives and normals up to `order` (0, 1 or 2). Reuses `out`'s storage.
/// Precondition: rows built from this surface's structure.
void evaluate_grid(const BSplineSurface& surface, const SamplingRows& u_rows,
                   const SamplingRows& v_rows, int order, SurfaceGrid& out);

/// Bezier patch of element (element_u, element_v) (indices into
/// extraction().spans): B = E_u * P_local * E_v^T in homogeneous coordinates.
BezierPatch bezier_patch(const BSplineSurface& surface, const SurfaceOperators& ops, int element_u,
                         int element_v);

/// Node positions: the surface at the Greville grid (xi_u_i, xi_v_j), row i * n_v + j.
ControlNet evaluate_nodes(const BSplineSurface& surface, const SurfaceOperators& ops);

/// Control points whose surface passes through `nodes` at the Greville grid,
/// keeping the surface's weights: two banded solves per direction, O(n p).
/// For a rational surface the nodes are lifted to homogeneous form with the
/// weight function at the nodes, so the fit stays exact.
ControlNet fit_control_points(const BSplineSurface& surface, const SurfaceOperators& ops,
                              const ControlNet& nodes);

/// Weight function sum N_i N_j w_ij at the Greville grid, row i * n_v + j
/// (ones for a polynomial surface).
Eigen::VectorXd weights_at_nodes(const BSplineSurface& surface, const SurfaceOperators& ops);

/// The transpose of fit_control_points: generalised forces on the control
/// points ((n_u * n_v) x c, any c columns) to generalised forces on the nodes,
/// such that Q . dP = G . dx for every node motion dx and dP = Fit(dx). A force
/// F at S(u, v) is Q_ij = R_ij(u, v) F on the control points (R the rational
/// basis); its node forces G sum to F and have the moment S(u, v) x F, exactly.
Eigen::MatrixXd fit_adjoint(const BSplineSurface& surface, const SurfaceOperators& ops,
                            const Eigen::MatrixXd& control_forces);

}  // namespace argil
