#include "argil/core/collision/surface_penetration.hpp"

#include <algorithm>
#include <cmath>

#include "argil/core/collision/detail/patch_minimize.hpp"
#include "argil/core/geometry/evaluate.hpp"

namespace argil {

namespace {

/// The box of `uv` grown by half its size each way (at least 1% of the
/// domain), clamped to the surface's domain.
ParamRect grown_box(const BSplineSurface& s, std::span<const Contact> region, bool side_a) {
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d hi = -lo;
  for (const Contact& c : region) {
    const Eigen::Vector2d& uv = side_a ? c.uv_a : c.uv_b;
    lo = lo.cwiseMin(uv);
    hi = hi.cwiseMax(uv);
  }
  const ParamRect domain = domain_of(s);
  const Eigen::Vector2d start = domain.lower(), end = domain.upper();
  const Eigen::Vector2d grow = (0.5 * (hi - lo)).cwiseMax(0.01 * (end - start));
  lo = (lo - grow).cwiseMax(start);
  hi = (hi + grow).cwiseMin(end);
  return ParamRect::from_corners(lo, hi);
}

/// The local foot of x on a within the box: the nearest point found by Newton.
PatchMinimum foot_on(const BSplineSurface& a, const ParamRect& box, const Eigen::Vector3d& x) {
  return minimize_on_patch(a, box, [&x](const Eigen::Vector3d& p) {
    DistanceSample s;
    const Eigen::Vector3d d = p - x;
    s.value = 0.5 * d.squaredNorm();  // smooth at the foot, same minimiser as |d|
    s.gradient = d;
    s.hessian = Eigen::Matrix3d::Identity();
    return s;
  });
}

/// The point of b in the box lowest along -n below the plane through `origin`.
PatchMinimum lowest_below_plane(const BSplineSurface& b, const ParamRect& box,
                                const Eigen::Vector3d& origin, const Eigen::Vector3d& n) {
  const auto height = [&](const Eigen::Vector3d& p) {
    DistanceSample s;
    s.value = n.dot(p - origin);
    s.gradient = n;
    return s;
  };
  PatchMinimum best;
  best.value = std::numeric_limits<double>::infinity();
  for (const ParamRect& q : box.split()) {
    const PatchMinimum m = minimize_on_patch(b, q, height);
    if (m.value < best.value) best = m;
  }
  return best;
}

}  // namespace

std::optional<Penetration> deepest_penetration(const BSplineSurface& a, const BSplineSurface& b,
                                               std::span<const Contact> region) {
  std::optional<Penetration> out;
  if (region.empty()) return out;
  const ParamRect box_a = grown_box(a, region, true);
  const ParamRect box_b = grown_box(b, region, false);

  // Start from a's point and normal at the region's first contact.
  Eigen::Vector2d uv_a = region.front().uv_a;
  for (int round = 0; round < 8; ++round) {
    const SurfaceDerivatives da = evaluate_derivatives(a, uv_a[0], uv_a[1], 1);
    const Eigen::Vector3d n = unit_normal(da);
    if (n.isZero()) return out;  // degenerate point of a: no side is defined
    const PatchMinimum low = lowest_below_plane(b, box_b, da.point, n);
    if (!(low.value < 0.0)) return out;  // nothing of b is behind a's tangent plane
    const Eigen::Vector3d x = low.derivatives.point;
    const PatchMinimum foot = foot_on(a, box_a, x);
    const SurfaceDerivatives df = evaluate_derivatives(a, foot.uv[0], foot.uv[1], 1);
    const Eigen::Vector3d n_foot = unit_normal(df);
    const Eigen::Vector3d offset = x - df.point;
    if (n_foot.isZero() || offset.dot(n_foot) >= 0.0) return out;  // b's point is in front
    const double depth = offset.norm();
    const bool settled = out && std::abs(depth - out->depth) <= 1e-12 * (1.0 + depth);
    out = Penetration{depth, foot.uv, low.uv};
    if (settled) break;
    uv_a = foot.uv;
  }
  return out;
}

}  // namespace argil
