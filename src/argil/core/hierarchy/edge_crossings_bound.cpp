#include "argil/core/hierarchy/edge_crossings_bound.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "argil/core/hierarchy/normal_cone.hpp"

namespace argil {

namespace {

Eigen::Vector3d point(const BezierPatch& patch, int a, int b) {
  return patch.points.row(a * (patch.degree_v + 1) + b).head<3>().transpose();
}

}  // namespace

double chord_lean(const BezierPatch& patch, const Eigen::Vector3d& axis) {
  const int p = patch.degree_u, q = patch.degree_v;
  if (p > kMaxNormalConeDegree || q > kMaxNormalConeDegree) return 1.0;
  // Unit differences along s and along t (zero ones add nothing to a chord).
  std::array<Eigen::Vector3d, 2 * (kMaxNormalConeDegree + 1) * kMaxNormalConeDegree> unit;
  std::size_t n_s = 0, n = 0;
  Eigen::Vector3d sum_s = Eigen::Vector3d::Zero(), sum_t = Eigen::Vector3d::Zero();
  double lean = 0.0;  // the largest |axis . d| of a unit difference d
  const auto add = [&](const Eigen::Vector3d& d, Eigen::Vector3d& sum) {
    const double length = d.norm();
    if (!(length > 0.0)) return;
    unit[n] = d / length;
    lean = std::max(lean, std::abs(axis.dot(unit[n])));
    sum += unit[n];
    ++n;
  };
  for (int a = 0; a < p; ++a)
    for (int b = 0; b <= q; ++b) add(point(patch, a + 1, b) - point(patch, a, b), sum_s);
  n_s = n;
  for (int a = 0; a <= p; ++a)
    for (int b = 0; b < q; ++b) add(point(patch, a, b + 1) - point(patch, a, b), sum_t);
  if (!std::isfinite(lean)) return 1.0;
  // A chord takes the s differences with one sign and the t differences with
  // one sign; (+, -) and (-, +) are the same chords reversed, as are (+, +)
  // and (-, -). Its length is at least its component along the middle
  // direction m of its generators, which each contribute at least `share`.
  double share = 1.0;
  for (const double sign_t : {1.0, -1.0}) {
    const Eigen::Vector3d middle = sum_s + sign_t * sum_t;
    const double length = middle.norm();
    if (!(length > 0.0)) return 1.0;
    for (std::size_t k = 0; k < n; ++k)
      share = std::min(share, (k < n_s ? 1.0 : sign_t) * unit[k].dot(middle) / length);
  }
  return share > 0.0 ? lean / share : 1.0;
}

double edge_rise(const BezierPatch& patch, PatchEdge edge, const Eigen::Vector3d& axis) {
  const int p = patch.degree_u, q = patch.degree_v;
  const bool along_s = edge == PatchEdge::t0 || edge == PatchEdge::t1;
  const int fixed = edge == PatchEdge::t0 || edge == PatchEdge::s0 ? 0 : along_s ? q : p;
  const int count = along_s ? p : q;
  double rise = 1.0, side = 0.0;
  for (int k = 0; k < count; ++k) {
    const Eigen::Vector3d d = along_s ? point(patch, k + 1, fixed) - point(patch, k, fixed)
                                      : point(patch, fixed, k + 1) - point(patch, fixed, k);
    const double length = d.norm();
    if (!(length > 0.0)) continue;
    const double lean = axis.dot(d) / length;
    if (side == 0.0) side = lean > 0.0 ? 1.0 : -1.0;
    if (!(side * lean > 0.0)) return 0.0;
    rise = std::min(rise, side * lean);
  }
  // A collapsed edge is one point: it meets the other patch at most once.
  return side == 0.0 ? 1.0 : rise;
}

}  // namespace argil
