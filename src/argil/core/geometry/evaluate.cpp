#include "argil/core/geometry/evaluate.hpp"

#include <algorithm>
#include <cassert>
#include <limits>

#include "argil/core/geometry/basis.hpp"
#include "argil/core/geometry/detail/homogeneous_derivatives.hpp"

namespace argil {

using Vector4 = Eigen::Vector4d;

namespace {

constexpr int kN = kMaxDegree + 1;
using BasisRows = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, 3, kN>;

/// The homogeneous derivatives up to `Order` from the basis rows of spans
/// (su, sv): a template so the surface point's hot loop has no order tests.
template <int Order>
void contract(const BSplineSurface& s, int su, int sv, const BasisRows& bu, const BasisRows& bv,
              detail::HomogeneousDerivatives& h) {
  const int p = s.degree[0];
  const int q = s.degree[1];
  const bool rational = s.is_rational();
  for (int a = 0; a <= p; ++a) {
    // Contract over v first: one 4-vector per v-derivative order for this row.
    // Plain arrays: a pole packed into a 4-vector on the stack was reloaded
    // as pairs across two scalar stores (a store-forwarding stall on every
    // pole, most of this function's time).
    double r0[4] = {0, 0, 0, 0}, r1[4] = {0, 0, 0, 0}, r2[4] = {0, 0, 0, 0};
    for (int b = 0; b <= q; ++b) {
      const Eigen::Index k = s.pole_index(su - p + a, sv - q + b);
      const double w = rational ? s.weights[k] : 1.0;
      const double pw[4] = {w * s.control_points(k, 0), w * s.control_points(k, 1),
                            w * s.control_points(k, 2), w};
      for (int c = 0; c < 4; ++c) {
        r0[c] += bv(0, b) * pw[c];
        if constexpr (Order >= 1) r1[c] += bv(1, b) * pw[c];
        if constexpr (Order >= 2) r2[c] += bv(2, b) * pw[c];
      }
    }
    for (int c = 0; c < 4; ++c) {
      h.a00[c] += bu(0, a) * r0[c];
      if constexpr (Order >= 1) {
        h.a10[c] += bu(1, a) * r0[c];
        h.a01[c] += bu(0, a) * r1[c];
      }
      if constexpr (Order >= 2) {
        h.a20[c] += bu(2, a) * r0[c];
        h.a11[c] += bu(1, a) * r1[c];
        h.a02[c] += bu(0, a) * r2[c];
      }
    }
  }
}

}  // namespace

SurfaceDerivatives evaluate_derivatives(const BSplineSurface& s, double u, double v, int order) {
  assert(order >= 0 && order <= 2);
  const int p = s.degree[0];
  const int q = s.degree[1];
  const int nu = s.count(Direction::u);
  const int nv = s.count(Direction::v);
  u = std::clamp(u, s.domain_start(Direction::u), s.domain_end(Direction::u));
  v = std::clamp(v, s.domain_start(Direction::v), s.domain_end(Direction::v));
  const int su = find_span(p, s.knots[0], nu, u);
  const int sv = find_span(q, s.knots[1], nv, v);

  BasisRows bu(order + 1, p + 1);
  BasisRows bv(order + 1, q + 1);
  basis_derivatives(p, s.knots[0], su, u, order, bu);
  basis_derivatives(q, s.knots[1], sv, v, order, bv);

  detail::HomogeneousDerivatives h;
  switch (order) {
    case 0:
      contract<0>(s, su, sv, bu, bv, h);
      break;
    case 1:
      contract<1>(s, su, sv, bu, bv, h);
      break;
    default:
      contract<2>(s, su, sv, bu, bv, h);
  }

  return detail::cartesian(h, order);
}

Eigen::Vector3d evaluate(const BSplineSurface& s, double u, double v) {
  return evaluate_derivatives(s, u, v, 0).point;
}

Eigen::Vector3d unit_normal(const SurfaceDerivatives& d) {
  const Eigen::Vector3d n = d.du.cross(d.dv);
  const double length = n.norm();
  // At a collapsed edge one tangent is rounding noise: its cross product with
  // the other is then within a few ulps of |S_u| |S_v| scale, not a direction.
  const double scale = std::max(d.du.squaredNorm(), d.dv.squaredNorm());
  constexpr double kDegenerate = 64.0 * std::numeric_limits<double>::epsilon();
  if (!(length > kDegenerate * scale)) return Eigen::Vector3d::Zero();
  return n / length;
}

Eigen::Vector3d unit_normal(const BSplineSurface& surface, double u, double v) {
  const Eigen::Vector3d n = unit_normal(evaluate_derivatives(surface, u, v, 1));
  if (n.squaredNorm() > 0.0) return n;
  const SurfaceDerivatives d = evaluate_derivatives(surface, u, v, 2);
  // A collapsed tangent is rounding noise next to the other one.
  constexpr double kCollapsed = 1e-6;
  const double su = d.du.norm(), sv = d.dv.norm();
  Eigen::Vector3d limit = Eigen::Vector3d::Zero();
  double scale = 0.0;
  if (sv <= kCollapsed * su) {
    const double side = u >= surface.domain_end(Direction::u) ? -1.0 : 1.0;
    limit = side * d.du.cross(d.duv);
    scale = su * d.duv.norm();
  } else if (su <= kCollapsed * sv) {
    const double side = v >= surface.domain_end(Direction::v) ? -1.0 : 1.0;
    limit = side * d.duv.cross(d.dv);
    scale = sv * d.duv.norm();
  }
  const double length = limit.norm();
  constexpr double kDegenerate = 64.0 * std::numeric_limits<double>::epsilon();
  if (!(length > kDegenerate * scale)) return Eigen::Vector3d::Zero();
  return limit / length;
}

}  // namespace argil
