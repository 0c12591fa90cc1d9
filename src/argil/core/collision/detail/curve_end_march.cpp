#include "argil/core/collision/detail/curve_end_march.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "argil/core/collision/detail/curve_densifier.hpp"

namespace argil {

namespace {

/// At most this many points marched from one end.
constexpr std::size_t kMaxPoints = 10000;

/// A parameter on its domain edge whose rate along the curve points out of
/// the domain by more than this fraction of its surface's rate: the curve
/// leaves there (below it, the rate is rounding: the curve runs along the edge).
constexpr double kLeaving = 1e-6;

Eigen::Vector4d params_of(const PairPoint& p) {
  return {p.uv_a[0], p.uv_a[1], p.uv_b[0], p.uv_b[1]};
}

/// The tangent turned to run along `along` (zero when it has no direction).
CurveTangent oriented(CurveTangent t, const Eigen::Vector3d& along) {
  if (t.unit.dot(along) < 0.0) {
    t.unit = -t.unit;
    t.uv_a = -t.uv_a;
    t.uv_b = -t.uv_b;
  }
  return t;
}

}  // namespace

IntersectionCurve march_from_end(const SurfacePair& pair, const PairPoint& end,
                                 const Eigen::Vector3d& outward, double tolerance,
                                 const ChordStop& stop) {
  IntersectionCurve out;
  const Eigen::Vector4d lo(pair.a().domain_start(Direction::u), pair.a().domain_start(Direction::v),
                           pair.b().domain_start(Direction::u),
                           pair.b().domain_start(Direction::v));
  const Eigen::Vector4d hi(pair.a().domain_end(Direction::u), pair.a().domain_end(Direction::v),
                           pair.b().domain_end(Direction::u), pair.b().domain_end(Direction::v));
  CurveTangent t = oriented(curve_tangent(pair.eval_a, pair.eval_b, end.uv_a, end.uv_b), outward);
  // The curve must leave the end the way the piece does (within 60 degrees):
  // otherwise the end is a turn the tangent does not describe.
  if (t.unit.isZero(0.0) || !(outward.norm() > 0.0) ||
      !(t.unit.dot(outward) >= 0.5 * outward.norm()))
    return out;
  CurveDensifier densifier(pair, tolerance);
  PairPoint at = end;
  double step = 4.0 * tolerance;
  while (out.points.size() < kMaxPoints) {
    const Eigen::Vector4d x = params_of(at);
    Eigen::Vector4d rate(t.uv_a[0], t.uv_a[1], t.uv_b[0], t.uv_b[1]);
    // A parameter on its domain edge: the curve leaves the domain there, or
    // runs along the edge and the parameter stays on it. A step that would
    // leave a domain is cut at its edge.
    bool leaving = false;
    for (int k = 0; k < 4; ++k) {
      if (x[k] != lo[k] && x[k] != hi[k]) continue;
      const double surface_rate = (k < 2 ? t.uv_a : t.uv_b).norm();
      const double outward_rate = x[k] == hi[k] ? rate[k] : -rate[k];
      if (outward_rate > kLeaving * surface_rate) leaving = true;
      rate[k] = 0.0;
    }
    if (leaving) break;
    double fraction = 1.0;
    int edge = -1;  // the parameter whose domain edge cuts the step
    double edge_value = 0.0;
    for (int k = 0; k < 4; ++k) {
      const double to = x[k] + step * rate[k];
      const double bound = to > hi[k] ? hi[k] : to < lo[k] ? lo[k] : to;
      if (bound == to) continue;
      const double cut = (bound - x[k]) / (step * rate[k]);
      if (cut < fraction) {
        fraction = cut;
        edge = k;
        edge_value = bound;
      }
    }
    const double length = fraction * step;
    // At a domain's edge, leaving it.
    if (!(length > 1e-3 * tolerance)) break;
    Eigen::Vector4d next = (x + length * rate).cwiseMax(lo).cwiseMin(hi);
    // Exactly on the edge, so refinement holds it there.
    if (edge >= 0) next[edge] = edge_value;
    const PairPoint start{at.point + length * t.unit, next.head<2>(), next.tail<2>()};
    const std::optional<RefinedPair> r = refine_near(pair, start, true, length + tolerance);
    std::optional<IntersectionCurve> between;
    if (r) {
      const Eigen::Vector3d ahead = r->point - at.point;
      // Ahead along the curve, not back or across it.
      if (ahead.dot(t.unit) >= 0.5 * ahead.norm() && ahead.norm() > 1e-3 * tolerance)
        between = densifier.between(at, {r->point, r->uv_a, r->uv_b});
    }
    if (!between) {
      step *= 0.5;
      if (step < tolerance) break;
      continue;
    }
    const CurveTangent next_t = oriented(r->tangent, t.unit);
    between->points.push_back(r->point);
    between->uv_a.push_back(r->uv_a);
    between->uv_b.push_back(r->uv_b);
    // Up to the first chord that `stop` accepts (a whole chord is asked at
    // once: a long step must not pass the end of another piece unasked).
    bool stopped = false;
    Eigen::Vector3d from = at.point;
    for (std::size_t k = 0; k < between->points.size() && !stopped; ++k) {
      const Eigen::Vector3d& to = between->points[k];
      stopped = stop(from, to);
      out.points.push_back(to);
      out.uv_a.push_back(between->uv_a[k]);
      out.uv_b.push_back(between->uv_b[k]);
      from = to;
    }
    if (stopped || edge >= 0 || next_t.unit.isZero(0.0)) break;
    if (between->points.size() == 1) step *= 2.0;
    at = {r->point, r->uv_a, r->uv_b};
    t = next_t;
  }
  return out;
}

}  // namespace argil
