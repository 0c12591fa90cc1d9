#include "argil/core/patch_bound.hpp"

#include <algorithm>

namespace argil {

PatchBound bound_patch(const BezierPatch& patch) {
  const int p = patch.degree_u;
  const int q = patch.degree_v;
  const Eigen::Index count = patch.points.rows();
  Eigen::Matrix<double, Eigen::Dynamic, 3> b(count, 3);
  for (Eigen::Index k = 0; k < count; ++k) {
    b.row(k) = patch.points.row(k).head<3>() / patch.points(k, 3);
  }
  PatchBound out;
  out.box = {b.colwise().minCoeff().transpose(), b.colwise().maxCoeff().transpose()};
  out.center = 0.5 * (out.box.min + out.box.max);
  out.radius = (b.rowwise() - out.center.transpose()).rowwise().norm().maxCoeff();

  const Eigen::Vector3d c00 = b.row(0), c10 = b.row(p * (q + 1));
  const Eigen::Vector3d c01 = b.row(q), c11 = b.row(p * (q + 1) + q);
  out.corners[0] = c00;
  out.corners[1] = c10;
  out.corners[2] = c01;
  out.corners[3] = c11;

  // Net to bilinear: S - L = sum B_ij (b_ij - L(i/p, j/q)) for polynomial patches
  // (Bernstein polynomials reproduce bilinear functions).
  double net_gap = 0.0;
  for (int i = 0; i <= p; ++i) {
    const double s = static_cast<double>(i) / p;
    for (int j = 0; j <= q; ++j) {
      const double t = static_cast<double>(j) / q;
      const Eigen::Vector3d l =
          (1 - s) * (1 - t) * c00 + s * (1 - t) * c10 + (1 - s) * t * c01 + s * t * c11;
      net_gap = std::max(net_gap, (b.row(i * (q + 1) + j).transpose() - l).norm());
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
    const double corner_radius = std::max({(c00 - mid).norm(), (c10 - mid).norm(),
                                           (c01 - mid).norm(), (c11 - mid).norm()});
    rational_gap = (w_max / w_min - 1.0) * corner_radius;
  }
  // Bilinear to two triangles: L - T = t (1 - s) (c10 + c01 - c00 - c11) on
  // the triangle s >= t (symmetric on the other), at most a quarter of it.
  const double twist = 0.25 * (c10 + c01 - c00 - c11).norm();
  out.flatness = net_gap + rational_gap + twist;
  return out;
}

}  // namespace argil
