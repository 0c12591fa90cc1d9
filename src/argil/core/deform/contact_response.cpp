#include "argil/core/deform/contact_response.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <limits>

#include "argil/core/geometry/basis.hpp"

namespace argil {

std::vector<double> contact_shares(const std::vector<Contact>& contacts, double eps) {
  std::vector<double> shares;
  shares.reserve(contacts.size());
  double total = 0.0;
  for (const Contact& c : contacts) {
    // A floor keeps contacts reported at exactly -eps in the sum.
    shares.push_back(std::max(c.depth + eps, 1e-3 * eps));
    total += shares.back();
  }
  for (double& s : shares) s /= total;
  return shares;
}

PoleWeights pole_weights_at(const BSplineSurface& s, const std::vector<Eigen::Vector2d>& uvs,
                            const std::vector<double>& shares) {
  assert(uvs.size() == shares.size());
  if (uvs.empty()) return {};
  const int nu = s.count(Direction::u), nv = s.count(Direction::v);
  const int p = s.degree[0], q = s.degree[1];
  // Each point clamped to the domain, and its knot spans: the block of poles
  // the terms reach (not the whole net; a sort of the terms by pole cost a
  // sphere's 36-point discs more than the rest of the load).
  std::vector<Eigen::Vector2d> at(uvs.size());
  std::vector<std::array<int, 2>> spans(uvs.size());
  int i0 = std::numeric_limits<int>::max(), i1 = -1;
  int j0 = std::numeric_limits<int>::max(), j1 = -1;
  for (std::size_t k = 0; k < uvs.size(); ++k) {
    at[k] = {std::clamp(uvs[k].x(), s.domain_start(Direction::u), s.domain_end(Direction::u)),
             std::clamp(uvs[k].y(), s.domain_start(Direction::v), s.domain_end(Direction::v))};
    spans[k] = {find_span(p, s.knots[0], nu, at[k].x()), find_span(q, s.knots[1], nv, at[k].y())};
    i0 = std::min(i0, spans[k][0] - p);
    i1 = std::max(i1, spans[k][0]);
    j0 = std::min(j0, spans[k][1] - q);
    j1 = std::max(j1, spans[k][1]);
  }
  const int width = j1 - j0 + 1;
  const std::size_t cells = static_cast<std::size_t>(i1 - i0 + 1) * static_cast<std::size_t>(width);
  std::vector<double> sum(cells, 0.0);
  std::vector<char> touched(cells, 0);
  Eigen::MatrixXd bu(1, p + 1), bv(1, q + 1);
  std::vector<double> w(static_cast<std::size_t>((p + 1) * (q + 1)));
  // Each pole's terms summed in point order from 0, as a dense pattern would
  // (each share times the rational basis R_ij: the products, zeros skipped,
  // over their sum).
  for (std::size_t k = 0; k < uvs.size(); ++k) {
    const auto [su, sv] = spans[k];
    basis_derivatives(p, s.knots[0], su, at[k].x(), 0, bu);
    basis_derivatives(q, s.knots[1], sv, at[k].y(), 0, bv);
    double total = 0.0;
    for (int a = 0; a <= p; ++a)
      for (int b = 0; b <= q; ++b) {
        const Eigen::Index pole = s.pole_index(su - p + a, sv - q + b);
        double& value = w[static_cast<std::size_t>(a * (q + 1) + b)];
        value = bu(0, a) * bv(0, b) * (s.is_rational() ? s.weights[pole] : 1.0);
        if (value != 0.0) total += value;
      }
    for (int a = 0; a <= p; ++a)
      for (int b = 0; b <= q; ++b) {
        const double value = w[static_cast<std::size_t>(a * (q + 1) + b)];
        if (value == 0.0) continue;
        const std::size_t c =
            static_cast<std::size_t>((su - p + a - i0) * width + (sv - q + b - j0));
        sum[c] += shares[k] * (value / total);
        touched[c] = 1;
      }
  }
  PoleWeights out;
  for (std::size_t c = 0; c < cells; ++c) {
    if (!touched[c]) continue;
    const int i = i0 + static_cast<int>(c) / width, j = j0 + static_cast<int>(c) % width;
    out.emplace_back(static_cast<Eigen::Index>(i) * nv + j, sum[c]);
  }
  return out;
}

PoleWeights contact_pole_weights(const BSplineSurface& s, const std::vector<Contact>& contacts,
                                 const std::vector<double>& shares) {
  assert(contacts.size() == shares.size());
  std::vector<Eigen::Vector2d> uvs;
  uvs.reserve(contacts.size());
  for (const Contact& c : contacts) uvs.push_back(c.uv_a);
  return pole_weights_at(s, uvs, shares);
}

Eigen::VectorXd dense_pattern(const PoleWeights& weights, Eigen::Index count) {
  Eigen::VectorXd pattern = Eigen::VectorXd::Zero(count);
  for (const auto& [pole, w] : weights) pattern[pole] = w;
  return pattern;
}

Eigen::VectorXd contact_load_pattern(const BSplineSurface& s, const std::vector<Contact>& contacts,
                                     const std::vector<double>& shares) {
  return dense_pattern(contact_pole_weights(s, contacts, shares),
                       static_cast<Eigen::Index>(s.count(Direction::u)) * s.count(Direction::v));
}

FrictionOutcome coulomb_friction(const Eigen::Vector3d& spring_force,
                                 const Eigen::Vector3d& outward_normal, double mu,
                                 double stiffness) {
  FrictionOutcome out;
  out.normal_force = -spring_force.dot(outward_normal);
  out.tangential_force = spring_force + out.normal_force * outward_normal;
  const double pull = out.tangential_force.norm();
  const double limit = mu * std::max(out.normal_force, 0.0);
  if (out.normal_force > 0.0 && pull <= limit) return out;
  out.stick = false;
  if (pull > 0.0) out.slide = out.tangential_force * ((pull - limit) / (pull * stiffness));
  return out;
}

}  // namespace argil
