#include "support/random_surface.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace argil::test {

namespace {

/// Clamped knots on a random domain [a, b] with random interior values, some
/// repeated up to `degree` times.
Eigen::VectorXd random_knots(std::mt19937_64& rng, int degree, int count, bool repeats) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double a = -5.0 + 10.0 * unit(rng);
  const double b = a + 0.5 + 20.0 * unit(rng);
  const int interior = count - degree - 1;
  std::vector<double> inner;
  while (static_cast<int>(inner.size()) < interior) {
    const double t = a + (b - a) * (0.02 + 0.96 * unit(rng));
    int copies = 1;
    if (repeats && unit(rng) < 0.3) {
      copies = 1 + static_cast<int>(unit(rng) * degree);
    }
    copies = std::min({copies, degree, interior - static_cast<int>(inner.size())});
    for (int c = 0; c < copies; ++c) inner.push_back(t);
  }
  std::sort(inner.begin(), inner.end());
  Eigen::VectorXd knots(count + degree + 1);
  Eigen::Index k = 0;
  for (int c = 0; c <= degree; ++c) knots[k++] = a;
  for (double t : inner) knots[k++] = t;
  for (int c = 0; c <= degree; ++c) knots[k++] = b;
  return knots;
}

}  // namespace

BSplineSurface random_surface(std::mt19937_64& rng, const RandomSurfaceOptions& o) {
  std::uniform_int_distribution<int> degree(o.min_degree, o.max_degree);
  std::uniform_int_distribution<int> extra(0, o.max_extra_poles);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  BSplineSurface s;
  for (int d = 0; d < 2; ++d) {
    s.degree[static_cast<std::size_t>(d)] = degree(rng);
    const int count = s.degree[static_cast<std::size_t>(d)] + 1 + extra(rng);
    s.knots[static_cast<std::size_t>(d)] =
        random_knots(rng, s.degree[static_cast<std::size_t>(d)], count, o.repeated_knots);
  }
  const int nu = s.count(Direction::u);
  const int nv = s.count(Direction::v);
  s.control_points.resize(static_cast<Eigen::Index>(nu) * nv, 3);
  const double phase = 6.28 * unit(rng);
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      const double x = o.size * i / std::max(1, nu - 1);
      const double y = o.size * j / std::max(1, nv - 1);
      const double z = 0.2 * o.size * std::sin(phase + 0.07 * x * 100.0 / o.size) *
                           std::cos(0.05 * y * 100.0 / o.size) +
                       0.05 * o.size * (unit(rng) - 0.5);
      s.control_points.row(s.pole_index(i, j)) << x + 0.02 * o.size * (unit(rng) - 0.5),
          y + 0.02 * o.size * (unit(rng) - 0.5), z;
    }
  }
  if (o.rational) {
    s.weights.resize(static_cast<Eigen::Index>(nu) * nv);
    for (Eigen::Index k = 0; k < s.weights.size(); ++k) {
      s.weights[k] = o.min_weight + (o.max_weight - o.min_weight) * unit(rng);
    }
  }
  return s;
}

BSplineSurface asymmetric_surface(bool rational) {
  BSplineSurface s;
  s.degree = {3, 2};
  // u: 7 poles, degree 3, interior knots 0.3, 0.3 (double), 0.75.
  s.knots[0].resize(11);
  s.knots[0] << 0.0, 0.0, 0.0, 0.0, 0.3, 0.3, 0.75, 1.0, 1.0, 1.0, 1.0;
  // v: 5 poles, degree 2, non-uniform on [-1, 2].
  s.knots[1].resize(8);
  s.knots[1] << -1.0, -1.0, -1.0, 0.1, 1.3, 2.0, 2.0, 2.0;
  const int nu = 7;
  const int nv = 5;
  s.control_points.resize(nu * nv, 3);
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      s.control_points.row(s.pole_index(i, j)) << 10.0 * i + 1.5 * j * j, 7.0 * j - 0.8 * i,
          3.0 * std::sin(0.9 * i + 0.4) * std::cos(1.3 * j) + 0.5 * i * j;
    }
  }
  if (rational) {
    s.weights.resize(nu * nv);
    for (int k = 0; k < nu * nv; ++k) s.weights[k] = 0.6 + 0.13 * ((k * 7) % 11);
  }
  return s;
}

}  // namespace argil::test
