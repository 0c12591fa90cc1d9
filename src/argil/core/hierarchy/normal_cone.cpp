#include "argil/core/hierarchy/normal_cone.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace argil {

namespace {

/// Binomial coefficients up to 2 kMaxNormalConeDegree - 1.
double binomial(int n, int k) {
  double c = 1.0;
  for (int i = 1; i <= k; ++i) c = c * (n - k + i) / i;
  return c;
}

/// Bernstein product weight: B^m_i B^n_k = w B^{m+n}_{i+k}.
double product_weight(int m, int i, int n, int k) {
  return binomial(m, i) * binomial(n, k) / binomial(m + n, i + k);
}

}  // namespace

std::optional<NormalCone> normal_cone(const BezierPatch& patch) {
  const int p = patch.degree_u, q = patch.degree_v;
  if (p < 1 || q < 1 || p > kMaxNormalConeDegree || q > kMaxNormalConeDegree) return std::nullopt;
  // Equal weights: the Cartesian net is the homogeneous one over a constant,
  // whose sign flips every normal alike (lines are what the cone is used for).
  const double w = patch.points(0, 3);
  if (!(patch.points.col(3).array() == w).all() || w == 0.0) return std::nullopt;
  const auto point = [&](int i, int j) -> Eigen::Vector3d {
    return patch.points.row(i * (q + 1) + j).head<3>().transpose();
  };
  // The normal's net N[I][J], I < 2p, J < 2q, up to the positive factor p q.
  constexpr int kMax = 2 * kMaxNormalConeDegree;
  std::array<Eigen::Vector3d, kMax * kMax> normals;
  const int nu = 2 * p, nv = 2 * q;
  for (int k = 0; k < nu * nv; ++k) normals[static_cast<std::size_t>(k)].setZero();
  // The net's differences and the product weights, each computed once (the
  // sum below takes every combination: p (q + 1) (p + 1) q terms).
  constexpr int kSide = kMaxNormalConeDegree + 1;
  std::array<Eigen::Vector3d, kSide * kSide> du, dv;  // du[i][j], i < p; dv[k][l], l < q
  std::array<double, kSide * kSide> wu, wv;           // wu[i][k]; wv[j][l]
  for (int i = 0; i < p; ++i)
    for (int j = 0; j <= q; ++j)
      du[static_cast<std::size_t>(i * kSide + j)] = point(i + 1, j) - point(i, j);
  for (int k = 0; k <= p; ++k)
    for (int l = 0; l < q; ++l)
      dv[static_cast<std::size_t>(k * kSide + l)] = point(k, l + 1) - point(k, l);
  for (int i = 0; i < p; ++i)
    for (int k = 0; k <= p; ++k)
      wu[static_cast<std::size_t>(i * kSide + k)] = product_weight(p - 1, i, p, k);
  for (int j = 0; j <= q; ++j)
    for (int l = 0; l < q; ++l)
      wv[static_cast<std::size_t>(j * kSide + l)] = product_weight(q, j, q - 1, l);
  for (int i = 0; i < p; ++i) {
    for (int j = 0; j <= q; ++j) {
      const Eigen::Vector3d& d_u = du[static_cast<std::size_t>(i * kSide + j)];
      for (int k = 0; k <= p; ++k) {
        const double w_u = wu[static_cast<std::size_t>(i * kSide + k)];
        for (int l = 0; l < q; ++l) {
          normals[static_cast<std::size_t>((i + k) * nv + j + l)] +=
              (w_u * wv[static_cast<std::size_t>(j * kSide + l)]) *
              d_u.cross(dv[static_cast<std::size_t>(k * kSide + l)]);
        }
      }
    }
  }
  double largest = 0.0;
  for (int k = 0; k < nu * nv; ++k)
    largest = std::max(largest, normals[static_cast<std::size_t>(k)].norm());
  if (!(largest > 0.0)) return std::nullopt;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int k = 0; k < nu * nv; ++k) {
    Eigen::Vector3d& n = normals[static_cast<std::size_t>(k)];
    const double length = n.norm();
    // A vanishing control vector lets the normal vanish at a corner.
    if (!(length > 1e-12 * largest)) return std::nullopt;
    n /= length;
    sum += n;
  }
  if (!(sum.norm() > 0.0)) return std::nullopt;
  NormalCone cone;
  cone.axis = sum.normalized();
  double least_cos = 1.0;
  for (int k = 0; k < nu * nv; ++k)
    least_cos = std::min(least_cos, cone.axis.dot(normals[static_cast<std::size_t>(k)]));
  // A hair wider than the control vectors' spread, for rounding in acos.
  cone.half_angle = std::acos(std::clamp(least_cos, -1.0, 1.0)) + 1e-9;
  if (!(cone.half_angle < 0.5 * M_PI)) return std::nullopt;
  return cone;
}

double least_crossing_angle(const NormalCone& a, const NormalCone& b) {
  const double between = std::atan2(a.axis.cross(b.axis).norm(), a.axis.dot(b.axis));
  const double to_parallel = std::min(between, M_PI - between);
  return std::max(0.0, to_parallel - a.half_angle - b.half_angle);
}

}  // namespace argil
