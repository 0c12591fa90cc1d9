#include "argil/core/hierarchy/patch_bound.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace argil {

namespace {

/// Cartesian control points of a patch, without heap allocation.
using CartesianNet = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor,
                                   (kMaxDegree + 1) * (kMaxDegree + 1), 3>;

/// PatchBound::flatness from the Cartesian net and the corners
/// S(0,0), S(1,0), S(0,1), S(1,1).
double flatness_bound(const BezierPatch& patch, const CartesianNet& xyz,
                      const std::array<Eigen::Vector3d, 4>& corners) {
  const int p = patch.degree_u;
  const int q = patch.degree_v;
  const auto& [c00, c10, c01, c11] = corners;
  // Net to bilinear: S - L = sum B_ij (b_ij - L(i/p, j/q)) for polynomial patches
  // (Bernstein polynomials reproduce bilinear functions).
  double net_gap2 = 0.0;
  for (int i = 0; i <= p; ++i) {
    const double s = static_cast<double>(i) / p;
    for (int j = 0; j <= q; ++j) {
      const double t = static_cast<double>(j) / q;
      const Eigen::Vector3d l =
          (1 - s) * (1 - t) * c00 + s * (1 - t) * c10 + (1 - s) * t * c01 + s * t * c11;
      net_gap2 = std::max(net_gap2, (xyz.row(i * (q + 1) + j).transpose() - l).squaredNorm());
    }
  }
  // Rational: the rational basis differs from the Bernstein one by at most
  // (w_max / w_min - 1) in total, acting on the bilinear values at the net
  // nodes, which lie within the corners' bounding radius of their centre.
  const double w_min = patch.points.col(3).minCoeff();
  const double w_max = patch.points.col(3).maxCoeff();
  double rational_gap = 0.0;
  if (w_max > w_min) {
    const Eigen::Vector3d mid = 0.25 * (c00 + c10 + c01 + c11);
    const double corner_radius =
        std::max({(c00 - mid).norm(), (c10 - mid).norm(), (c01 - mid).norm(), (c11 - mid).norm()});
    rational_gap = (w_max / w_min - 1.0) * corner_radius;
  }
  // Bilinear to two triangles: L - T = t (1 - s) (c10 + c01 - c00 - c11) on
  // the triangle s >= t (symmetric on the other), at most a quarter of it.
  const double twist = 0.25 * (c10 + c01 - c00 - c11).norm();
  return std::sqrt(net_gap2) + rational_gap + twist;
}

}  // namespace

PatchBound bound_patch(const BezierPatch& patch) {
  const int p = patch.degree_u;
  const int q = patch.degree_v;
  const Eigen::Index count = patch.points.rows();
  // Cartesian control points, once (a node refresh runs this every tick).
  CartesianNet xyz(count, 3);
  for (Eigen::Index k = 0; k < count; ++k) {
    const double w = patch.points(k, 3);
    xyz.row(k) = patch.points.row(k).head<3>() / w;
  }
  const auto cartesian = [&xyz](Eigen::Index k) -> Eigen::Vector3d {
    return xyz.row(k).transpose();
  };
  PatchBound out;
  Eigen::Vector3d lo = cartesian(0), hi = lo;
  for (Eigen::Index k = 1; k < count; ++k) {
    const Eigen::Vector3d x = cartesian(k);
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  out.box = {lo, hi};
  out.center = 0.5 * (lo + hi);
  double r2 = 0.0;
  for (Eigen::Index k = 0; k < count; ++k)
    r2 = std::max(r2, (cartesian(k) - out.center).squaredNorm());
  out.radius = std::sqrt(r2);
  out.corners = {cartesian(0), cartesian(p * (q + 1)), cartesian(q), cartesian(p * (q + 1) + q)};
  out.flatness = flatness_bound(patch, xyz, out.corners);
  return out;
}

}  // namespace argil
