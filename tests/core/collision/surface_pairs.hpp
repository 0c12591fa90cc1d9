#pragma once
// Surface pairs for the surface-surface intersection tests: graph surfaces
// whose (x, y) is exactly (size u, size v), so crossings are sign changes of
// z_a - z_b at equal parameters (a brute-force oracle with no projection),
// and exact cylinder patches.

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "argil/core.hpp"
#include "support/built_hierarchy.hpp"
#include "support/polyline_distance.hpp"

namespace argil::test {

/// Clamped knots on [0, 1] with random interior knots, some repeated.
inline Eigen::VectorXd unit_knots(std::mt19937_64& rng, int degree, int count) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<double> inner;
  const int interior = count - degree - 1;
  while (static_cast<int>(inner.size()) < interior) {
    const double t = 0.05 + 0.9 * unit(rng);
    const int copies =
        std::min({unit(rng) < 0.2 ? 2 : 1, degree, interior - static_cast<int>(inner.size())});
    for (int c = 0; c < copies; ++c) inner.push_back(t);
  }
  std::sort(inner.begin(), inner.end());
  Eigen::VectorXd k(count + degree + 1);
  Eigen::Index n = 0;
  for (int c = 0; c <= degree; ++c) k[n++] = 0.0;
  for (double t : inner) k[n++] = t;
  for (int c = 0; c <= degree; ++c) k[n++] = 1.0;
  return k;
}

/// A polynomial graph z(x, y) over [0, size]^2 with (x, y) = size (u, v):
/// x and y control values at the Greville abscissae (linear precision).
/// z control values are random in [offset - amplitude, offset + amplitude].
inline BSplineSurface graph_surface(std::mt19937_64& rng, double size, double amplitude,
                                    double offset, int max_degree = 5, int max_extra = 3) {
  std::uniform_int_distribution<int> degree(1, max_degree);
  std::uniform_int_distribution<int> extra(0, max_extra);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  BSplineSurface s;
  for (std::size_t d = 0; d < 2; ++d) {
    s.degree[d] = degree(rng);
    s.knots[d] = unit_knots(rng, s.degree[d], s.degree[d] + 1 + extra(rng));
  }
  const Eigen::VectorXd gu = greville_abscissae(s.degree[0], s.knots[0]);
  const Eigen::VectorXd gv = greville_abscissae(s.degree[1], s.knots[1]);
  s.control_points.resize(gu.size() * gv.size(), 3);
  for (int i = 0; i < gu.size(); ++i)
    for (int j = 0; j < gv.size(); ++j)
      s.control_points.row(s.pole_index(i, j)) << size * gu[i], size * gv[j],
          offset + amplitude * unit(rng);
  return s;
}

/// Quarter cylinder of radius r around the x axis (y, z from (0, -r) to
/// (r, 0)), x in [x0, x1]: an exact rational quadratic arc in u.
inline BSplineSurface cylinder_x(double r, double x0, double x1) {
  BSplineSurface s;
  s.degree = {2, 1};
  s.knots[0].resize(6);
  s.knots[0] << 0, 0, 0, 1, 1, 1;
  s.knots[1].resize(4);
  s.knots[1] << 0, 0, 1, 1;
  s.control_points.resize(6, 3);
  s.control_points << x0, 0, -r, x1, 0, -r, x0, r, -r, x1, r, -r, x0, r, 0, x1, r, 0;
  s.weights.resize(6);
  s.weights << 1, 1, std::sqrt(0.5), std::sqrt(0.5), 1, 1;
  return s;
}

/// The surface moved rigidly: x -> R x + t (weights kept).
inline BSplineSurface moved(const BSplineSurface& s, const Eigen::Matrix3d& R,
                            const Eigen::Vector3d& t) {
  BSplineSurface m = s;
  m.control_points = ((s.control_points * R.transpose()).rowwise() + t.transpose()).eval();
  return m;
}

/// Distance from p to the reported curves (their polylines).
inline double distance_to_curves(const Eigen::Vector3d& p, const CollisionResult& r) {
  double best = std::numeric_limits<double>::infinity();
  for (const IntersectionCurve& c : r.curves)
    best = std::min(best, test::distance_to_polyline(p, c.points));
  return best;
}

/// Distance from p to the reported set: curve polylines and contact points.
inline double distance_to_result(const Eigen::Vector3d& p, const CollisionResult& r) {
  double best = distance_to_curves(p, r);
  for (const Contact& c : r.contacts) best = std::min(best, (c.point - p).norm());
  return best;
}

/// A clamped uniform bicubic n x n net over the unit square, poles at
/// (i / (n - 1), j / (n - 1), z(x, y)).
inline BSplineSurface unit_net(int n, const std::function<double(double, double)>& z) {
  BSplineSurface s;
  s.degree = {3, 3};
  for (std::size_t d = 0; d < 2; ++d) {
    s.knots[d].resize(n + 4);
    for (int k = 0; k < n + 4; ++k)
      s.knots[d][k] = std::clamp(static_cast<double>(k - 3) / (n - 3), 0.0, 1.0);
  }
  s.control_points.resize(n * n, 3);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double x = static_cast<double>(i) / (n - 1), y = static_cast<double>(j) / (n - 1);
      s.control_points.row(s.pole_index(i, j)) << x, y, z(x, y);
    }
  return s;
}

/// The wavy pair: a 16x16 net z = 0.08 sin(2 pi x) cos(2 pi y) crossed by an
/// 8x8 net z = 0.25 (x - 0.5) + 0.02 cos(3 pi y), in one curve from y = 0 to
/// y = 1 through leaves of many sizes.
inline std::pair<BSplineSurface, BSplineSurface> wavy_pair() {
  constexpr double kPi = 3.14159265358979323846;
  return {
      unit_net(16, [](double x,
                      double y) { return 0.08 * std::sin(2 * kPi * x) * std::cos(2 * kPi * y); }),
      unit_net(8,
               [](double x, double y) { return 0.25 * (x - 0.5) + 0.02 * std::cos(3 * kPi * y); })};
}

/// Two random graph surfaces over [0, 100]^2 (amplitude 2, degree up to 4),
/// b lifted by an offset that ranges from crossing to a gap near eps = 0.1 to
/// clearly apart: a fixed 4.5 for every third trial, random in [-4, 4] else.
inline std::pair<BSplineSurface, BSplineSurface> random_offset_pair(std::mt19937_64& rng,
                                                                    int trial) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  BSplineSurface a = graph_surface(rng, 100.0, 2.0, 0.0, 4, 3);
  BSplineSurface b = graph_surface(rng, 100.0, 2.0, 0.0, 4, 3);
  b.control_points.col(2).array() += (trial % 3 == 0 ? 4.5 : 8.0 * (unit(rng) - 0.5));
  return {std::move(a), std::move(b)};
}

/// True when the two results list the very same contacts (points and depths,
/// in order).
inline bool same_contacts(const CollisionResult& x, const CollisionResult& y) {
  if (x.contacts.size() != y.contacts.size()) return false;
  for (std::size_t k = 0; k < x.contacts.size(); ++k)
    if (x.contacts[k].point != y.contacts[k].point || x.contacts[k].depth != y.contacts[k].depth)
      return false;
  return true;
}

}  // namespace argil::test
