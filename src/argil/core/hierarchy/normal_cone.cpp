#include "argil/core/hierarchy/normal_cone.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace argil {

namespace {

/// Binomial coefficients up to 2 kMaxNormalConeDegree - 1.
constexpr double binomial(int n, int k) {
  double c = 1.0;
  for (int i = 1; i <= k; ++i) c = c * (n - k + i) / i;
  return c;
}

/// Bernstein product weight: B^m_i B^n_k = w B^{m+n}_{i+k}.
constexpr double product_weight(int m, int i, int n, int k) {
  return binomial(m, i) * binomial(n, k) / binomial(m + n, i + k);
}

/// A degree the compiler knows (bicubic and lower, most CAD faces: it then
/// unrolls the loops and folds the weights), or kAnyDegree: the patch's own.
constexpr int kAnyDegree = -1;
constexpr int kSide = kMaxNormalConeDegree + 1;

/// The product weights a degree (p, q) patch's normal net takes: wu[i][k]
/// for the u differences (i < p) against the v differences' rows (k <= p),
/// wv[j][l] for the rows (j <= q) against the v differences (l < q).
struct ProductWeights {
  std::array<double, kSide * kSide> wu{}, wv{};
};

constexpr ProductWeights product_weights(int p, int q) {
  ProductWeights w;
  for (int i = 0; i < p; ++i)
    for (int k = 0; k <= p; ++k)
      w.wu[static_cast<std::size_t>(i * kSide + k)] = product_weight(p - 1, i, p, k);
  for (int j = 0; j <= q; ++j)
    for (int l = 0; l < q; ++l)
      w.wv[static_cast<std::size_t>(j * kSide + l)] = product_weight(q, j, q - 1, l);
  return w;
}

/// Folded at compile time for a known degree; the same arithmetic either way.
template <int P, int Q>
struct KnownWeights {
  static constexpr ProductWeights value = product_weights(P, Q);
};

/// The cone around the normal's control vectors of a degree P x Q patch (or
/// of its own degrees); nullopt when one vanishes or no cone narrower than a
/// half space holds them.
template <int P, int Q>
std::optional<NormalCone> cone_of(const BezierPatch& patch) {
  const int p = P == kAnyDegree ? patch.degree_u : P;
  const int q = Q == kAnyDegree ? patch.degree_v : Q;
  const auto point = [&](int i, int j) -> Eigen::Vector3d {
    return patch.points.row(i * (q + 1) + j).head<3>().transpose();
  };
  // The normal's net N[I][J], I < 2p, J < 2q, up to the positive factor p q.
  constexpr int kMax = 2 * kMaxNormalConeDegree;
  std::array<Eigen::Vector3d, kMax * kMax> normals;
  const int nu = 2 * p, nv = 2 * q;
  for (int k = 0; k < nu * nv; ++k) normals[static_cast<std::size_t>(k)].setZero();
  // The net's differences, each computed once (the sum below takes every
  // combination: p (q + 1) (p + 1) q terms).
  std::array<Eigen::Vector3d, kSide * kSide> du, dv;  // du[i][j], i < p; dv[k][l], l < q
  for (int i = 0; i < p; ++i)
    for (int j = 0; j <= q; ++j)
      du[static_cast<std::size_t>(i * kSide + j)] = point(i + 1, j) - point(i, j);
  for (int k = 0; k <= p; ++k)
    for (int l = 0; l < q; ++l)
      dv[static_cast<std::size_t>(k * kSide + l)] = point(k, l + 1) - point(k, l);
  ProductWeights runtime;
  if constexpr (P == kAnyDegree || Q == kAnyDegree) runtime = product_weights(p, q);
  const ProductWeights& w =
      P == kAnyDegree || Q == kAnyDegree ? runtime : KnownWeights<P, Q>::value;
  for (int i = 0; i < p; ++i) {
    for (int j = 0; j <= q; ++j) {
      const Eigen::Vector3d& d_u = du[static_cast<std::size_t>(i * kSide + j)];
      for (int k = 0; k <= p; ++k) {
        const double w_u = w.wu[static_cast<std::size_t>(i * kSide + k)];
        for (int l = 0; l < q; ++l) {
          normals[static_cast<std::size_t>((i + k) * nv + j + l)] +=
              (w_u * w.wv[static_cast<std::size_t>(j * kSide + l)]) *
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

}  // namespace

std::optional<NormalCone> normal_cone(const BezierPatch& patch) {
  const int p = patch.degree_u, q = patch.degree_v;
  if (p < 1 || q < 1 || p > kMaxNormalConeDegree || q > kMaxNormalConeDegree) return std::nullopt;
  // Equal weights: the Cartesian net is the homogeneous one over a constant,
  // whose sign flips every normal alike (lines are what the cone is used for).
  const double w = patch.points(0, 3);
  if (!(patch.points.col(3).array() == w).all() || w == 0.0) return std::nullopt;
  using Cone = std::optional<NormalCone> (*)(const BezierPatch&);
  static constexpr Cone kLow[3][3] = {{cone_of<1, 1>, cone_of<1, 2>, cone_of<1, 3>},
                                      {cone_of<2, 1>, cone_of<2, 2>, cone_of<2, 3>},
                                      {cone_of<3, 1>, cone_of<3, 2>, cone_of<3, 3>}};
  if (p <= 3 && q <= 3) return kLow[p - 1][q - 1](patch);
  return cone_of<kAnyDegree, kAnyDegree>(patch);
}

double least_crossing_angle(const NormalCone& a, const NormalCone& b) {
  const double between = std::atan2(a.axis.cross(b.axis).norm(), a.axis.dot(b.axis));
  const double to_parallel = std::min(between, M_PI - between);
  return std::max(0.0, to_parallel - a.half_angle - b.half_angle);
}

}  // namespace argil
