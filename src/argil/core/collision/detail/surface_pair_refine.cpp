#include "argil/core/collision/detail/surface_pair_refine.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <limits>
#include <optional>

#include "argil/core/geometry/evaluate.hpp"

namespace argil {

namespace {

/// What keeps an on-curve point from sliding along the curve: parameters
/// fixed on their domain edges where the curve crosses them, or else a plane
/// across the curve (also beside fixed parameters when the curve runs along
/// their edges: there they do not pin the point).
struct CurveConstraint {
  std::array<bool, 4> fixed{false, false, false, false};
  Eigen::Vector3d plane_normal = Eigen::Vector3d::Zero();  // zero: no plane
  Eigen::Vector3d plane_point = Eigen::Vector3d::Zero();
};

/// True when the fixed parameters pin a curve point: both of one surface's,
/// or one whose iso-line (the edge it holds the point on) crosses the curve's
/// unit tangent `t`. A curve along that edge (two faces meeting edge to edge,
/// a face's edge lying on another face) leaves the point free to slide along
/// it, a direction the Gauss-Newton step does not see.
bool pinned_by_fixed(const SurfaceDerivatives& da, const SurfaceDerivatives& db,
                     const std::array<bool, 4>& fixed, const Eigen::Vector3d& t) {
  constexpr double kAlongSine = 1e-6;  // the iso-line runs along the curve
  const auto pins = [&](const SurfaceDerivatives& d, bool u_fixed, bool v_fixed) {
    if (u_fixed && v_fixed) return true;
    if (!u_fixed && !v_fixed) return false;
    const Eigen::Vector3d& along = u_fixed ? d.dv : d.du;  // the iso-line's direction
    const double length = along.norm();
    return !(length > 0.0) || along.cross(t).norm() > kAlongSine * length;
  };
  return pins(da, fixed[0], fixed[1]) || pins(db, fixed[2], fixed[3]);
}

/// From the surfaces' derivatives at the start x, with parameter `fixed`
/// (-1: none) held as if on its domain edge.
CurveConstraint curve_constraint(const SurfaceDerivatives& da, const SurfaceDerivatives& db,
                                 const Eigen::Vector4d& x, const Eigen::Vector4d& lo,
                                 const Eigen::Vector4d& hi, int fixed) {
  CurveConstraint c;
  for (int k = 0; k < 4; ++k) {
    if (x[k] == lo[k] || x[k] == hi[k] || k == fixed) c.fixed[static_cast<std::size_t>(k)] = true;
  }
  const Eigen::Vector3d t = unit_normal(da).cross(unit_normal(db));
  // Tangent surfaces have no curve direction: fall back to closest points.
  if (!(t.norm() > 1e-8)) return c;
  const Eigen::Vector3d unit = t.normalized();
  if (pinned_by_fixed(da, db, c.fixed, unit)) return c;
  c.plane_normal = unit;
  c.plane_point = 0.5 * (da.point + db.point);
  return c;
}

/// Below this fraction of the largest pivot, a direction of the scaled
/// (unit-column) Gauss-Newton matrix is taken as absent: the surfaces are
/// parallel along it to within 1e-10 radians.
constexpr double kRankCut = 1e-10;

/// The scaled Gauss-Newton matrix, at most 4 x 4, on the stack: a curve
/// refines thousands of points, and a heap-sized solve spent more on
/// allocation than on arithmetic.
using SmallMatrix = Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::ColMajor, 4, 4>;

/// The step from the N free columns of `ms` (its N rows) by LU: square and
/// well conditioned (a transversal crossing, or a point held on a leaf edge
/// without the plane), its one solution is the minimum-norm one, at a
/// fraction of the cost; held columns are zero and their entries stay 0. The
/// columns have unit norm; nullopt at a pivot below 1e-8 (rank deficient).
template <int N>
std::optional<Eigen::Vector4d> square_step(const SmallMatrix& ms,
                                           const Eigen::Matrix<double, 5, 1>& rhs,
                                           const std::array<bool, 4>& fixed) {
  std::array<int, N> free{};
  Eigen::Matrix<double, N, N> square;
  for (int k = 0, c = 0; k < 4; ++k) {
    if (fixed[static_cast<std::size_t>(k)]) continue;
    free[static_cast<std::size_t>(c)] = k;
    square.col(c++) = ms.col(k);
  }
  const Eigen::PartialPivLU<Eigen::Matrix<double, N, N>> lu{square};
  if (!(lu.matrixLU().diagonal().cwiseAbs().minCoeff() > 1e-8)) return std::nullopt;
  const Eigen::Matrix<double, N, 1> solved = lu.solve(rhs.template head<N>());
  Eigen::Vector4d step = Eigen::Vector4d::Zero();
  for (int c = 0; c < N; ++c) step[free[static_cast<std::size_t>(c)]] = solved[c];
  return step;
}

/// The minimum-norm Gauss-Newton step in (u_a, v_a, u_b, v_b) for
/// S_a - S_b = 0 under the constraint.
Eigen::Vector4d gauss_newton_step(const SurfaceDerivatives& da, const SurfaceDerivatives& db,
                                  const CurveConstraint& constraint) {
  Eigen::Matrix<double, 5, 4> m = Eigen::Matrix<double, 5, 4>::Zero();
  Eigen::Matrix<double, 5, 1> rhs = Eigen::Matrix<double, 5, 1>::Zero();
  m.block<3, 1>(0, 0) = da.du;
  m.block<3, 1>(0, 1) = da.dv;
  m.block<3, 1>(0, 2) = -db.du;
  m.block<3, 1>(0, 3) = -db.dv;
  rhs.head<3>() = -(da.point - db.point);
  int rows = 3;
  if (constraint.plane_normal.squaredNorm() > 0) {
    const Eigen::Vector3d& n = constraint.plane_normal;
    m(3, 0) = n.dot(da.du);
    m(3, 1) = n.dot(da.dv);
    rhs[3] = -n.dot(da.point - constraint.plane_point);
    rows = 4;
  }
  // Edge parameters stay put: their columns drop out of the step.
  for (int k = 0; k < 4; ++k)
    if (constraint.fixed[static_cast<std::size_t>(k)]) m.col(k).setZero();
  // Column scaling keeps the minimum-norm step meaningful when u and s
  // live on very different parameter ranges.
  Eigen::Vector4d col_scale;
  for (int k = 0; k < 4; ++k) {
    const double n = m.col(k).head(rows).norm();
    col_scale[k] = n > 0 ? 1.0 / n : 1.0;
  }
  const SmallMatrix ms = m.topRows(rows) * col_scale.asDiagonal();
  const auto free_count = 4 - std::count(constraint.fixed.begin(), constraint.fixed.end(), true);
  std::optional<Eigen::Vector4d> step;
  if (rows == 4 && free_count == 4) step = square_step<4>(ms, rhs, constraint.fixed);
  if (rows == 3 && free_count == 3) step = square_step<3>(ms, rhs, constraint.fixed);
  if (step) return col_scale.cwiseProduct(*step);
  const Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, 4, 1> r = rhs.head(rows);
  // Eigen's default rank cut (about 1e-15) keeps directions made of rounding:
  // a face edge lying in the other face's plane gives the out-of-plane row
  // only rounding in both matrix and residual, and their ratio slid points
  // along the curve by a millimetre, onto the edge's end.
  Eigen::CompleteOrthogonalDecomposition<SmallMatrix> cod(ms);
  cod.setThreshold(kRankCut);
  return col_scale.cwiseProduct(Eigen::Vector4d(cod.solve(r)));
}

/// The curve's direction from both surfaces' first derivatives.
CurveTangent tangent_from(const SurfaceDerivatives& da, const SurfaceDerivatives& db) {
  const Eigen::Vector3d na = da.du.cross(da.dv), nb = db.du.cross(db.dv);
  const Eigen::Vector3d t = na.cross(nb);
  const double length = t.norm();
  // Below 1e-8 of |n_a| |n_b| the normals are parallel to rounding: no direction.
  if (!(length > 1e-8 * na.norm() * nb.norm())) return {};
  const Eigen::Vector3d unit = t / length;
  // d(uv)/ds solves [S_u S_v] d(uv) = T; T lies in both tangent planes, so
  // the normal equations are exact up to rounding.
  const auto rate = [&unit](const SurfaceDerivatives& d) -> Eigen::Vector2d {
    Eigen::Matrix2d g;
    g << d.du.dot(d.du), d.du.dot(d.dv), d.du.dot(d.dv), d.dv.dot(d.dv);
    if (!(g.determinant() > 1e-12 * g(0, 0) * g(1, 1))) return Eigen::Vector2d::Zero();
    return g.inverse() * Eigen::Vector2d(d.du.dot(unit), d.dv.dot(unit));
  };
  const Eigen::Vector2d ra = rate(da), rb = rate(db);
  if (ra.isZero(0.0) || rb.isZero(0.0)) return {};
  return {unit, ra, rb};
}

}  // namespace

RefinedPair refine_surface_pair(PatchEvaluator& eval_a, PatchEvaluator& eval_b,
                                const PairRefineRequest& request) {
  const BSplineSurface& a = eval_a.surface();
  const BSplineSurface& b = eval_b.surface();
  Eigen::Vector4d x(request.uv_a[0], request.uv_a[1], request.uv_b[0], request.uv_b[1]);
  const Eigen::Vector4d lo(a.domain_start(Direction::u), a.domain_start(Direction::v),
                           b.domain_start(Direction::u), b.domain_start(Direction::v));
  const Eigen::Vector4d hi(a.domain_end(Direction::u), a.domain_end(Direction::v),
                           b.domain_end(Direction::u), b.domain_end(Direction::v));
  // The surfaces at x: the start's derivatives serve the constraint and the
  // first iteration, and the last iteration's points the result.
  SurfaceDerivatives da = eval_a.evaluate(x[0], x[1], 1);
  SurfaceDerivatives db = eval_b.evaluate(x[2], x[3], 1);
  bool evaluated = true;
  const CurveConstraint constraint =
      request.on_curve ? curve_constraint(da, db, x, lo, hi, request.fixed) : CurveConstraint{};
  RefinedPair out;
  const double stop = 1e-14 * request.scale;
  constexpr int kMaxIterations = 40;
  double previous = std::numeric_limits<double>::infinity();
  for (int it = 0; it < kMaxIterations; ++it) {
    if (!evaluated) {
      da = eval_a.evaluate(x[0], x[1], 1);
      db = eval_b.evaluate(x[2], x[3], 1);
      evaluated = true;
    }
    out.iterations = it;
    const double residual = (da.point - db.point).norm();
    if (residual <= stop) break;
    // Gauss-Newton stalls once rounding dominates: stop when |F| stops shrinking.
    if (it > 3 && residual >= 0.5 * previous) break;
    previous = residual;
    const Eigen::Vector4d next =
        (x + gauss_newton_step(da, db, constraint)).cwiseMax(lo).cwiseMin(hi);
    if (next == x) break;
    x = next;
    evaluated = false;
  }
  if (!evaluated) {
    da = eval_a.evaluate(x[0], x[1], 1);
    db = eval_b.evaluate(x[2], x[3], 1);
  }
  out.uv_a = x.head<2>();
  out.uv_b = x.tail<2>();
  out.point = 0.5 * (da.point + db.point);
  out.gap = (da.point - db.point).norm();
  out.tangent = tangent_from(da, db);
  return out;
}

CurveTangent curve_tangent(PatchEvaluator& a, PatchEvaluator& b, const Eigen::Vector2d& uv_a,
                           const Eigen::Vector2d& uv_b) {
  return tangent_from(a.evaluate(uv_a[0], uv_a[1], 1), b.evaluate(uv_b[0], uv_b[1], 1));
}

std::optional<RefinedPair> refine_near(const SurfacePair& pair, const PairPoint& start,
                                       bool on_curve, double reach, int fixed) {
  const RefinedPair r = refine_surface_pair(pair.eval_a, pair.eval_b,
                                            {.uv_a = start.uv_a,
                                             .uv_b = start.uv_b,
                                             .on_curve = on_curve,
                                             .fixed = fixed,
                                             .scale = pair.scale});
  if (!((r.point - start.point).norm() <= reach)) return std::nullopt;
  // Converged means on both surfaces up to rounding of the model size.
  if (on_curve && !(r.gap <= 1e-12 * pair.scale)) return std::nullopt;
  return r;
}

}  // namespace argil
