#include "argil/core/deform/contact_footprint.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cassert>
#include <cmath>

#include "argil/core/deform/contact_response.hpp"
#include "argil/core/geometry/param_rect.hpp"

namespace argil {

namespace {

/// The disc's sample points: rings at (j + 1/2) a / 3 with 6, 12, 18 points,
/// each turned half a step (so the set is symmetric about the first axis),
/// each weighted by the pressure 1 - rho^2 / a^2 times its share of the
/// disc's area (midpoint rule in rho).
struct DiscSample {
  Eigen::Vector2d offset;  // in units of the radius, in the tangent frame
  double weight;
};

const std::vector<DiscSample>& disc_samples() {
  static const std::vector<DiscSample> samples = [] {
    std::vector<DiscSample> out;
    constexpr int kRings = 3;
    for (int j = 0; j < kRings; ++j) {
      const double rho = (j + 0.5) / kRings;
      const int n = 6 * (j + 1);
      const double turn = M_PI / n;
      for (int k = 0; k < n; ++k) {
        const double theta = turn + 2.0 * M_PI * k / n;
        out.push_back({{rho * std::cos(theta), rho * std::sin(theta)},
                       (1.0 - rho * rho) * rho / (kRings * n)});
      }
    }
    return out;
  }();
  return samples;
}

}  // namespace

double sphere_contact_radius(double sphere_radius, double force, double foundation) {
  if (!(force > 0.0) || !(sphere_radius > 0.0)) return 0.0;
  if (!(foundation > 0.0)) return sphere_radius;
  const double a = std::pow(4.0 * sphere_radius * force / (M_PI * foundation), 0.25);
  return std::min(a, sphere_radius);
}

Eigen::VectorXd footprint_load_pattern(const BSplineSurface& s,
                                       const std::vector<Contact>& contacts,
                                       const std::vector<double>& shares, double radius,
                                       const TrimRegion& trim) {
  return dense_pattern(footprint_pole_weights(s, contacts, shares, radius, trim),
                       static_cast<Eigen::Index>(s.count(Direction::u)) * s.count(Direction::v));
}

PoleWeights footprint_pole_weights(const BSplineSurface& s, const std::vector<Contact>& contacts,
                                   const std::vector<double>& shares, double radius,
                                   const TrimRegion& trim) {
  assert(contacts.size() == shares.size());
  if (!(radius > 0.0)) return contact_pole_weights(s, contacts, shares);
  const ParamRect domain{s.domain_start(Direction::u), s.domain_end(Direction::u),
                         s.domain_start(Direction::v), s.domain_end(Direction::v)};
  // The points that carry the load, and their shares of it.
  std::vector<Eigen::Vector2d> points;
  std::vector<double> weights;
  points.reserve(contacts.size() * disc_samples().size());
  weights.reserve(points.capacity());
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const Contact& c = contacts[k];
    Eigen::Matrix<double, 3, 2> jacobian;
    jacobian << c.tangent_u, c.tangent_v;
    const Eigen::Matrix2d metric = jacobian.transpose() * jacobian;
    const double det = metric.determinant();
    // A degenerate point (a collapsed edge) has no tangent plane to spread over.
    if (!(det > 1e-12 * metric.squaredNorm())) {
      points.push_back(c.uv_a);
      weights.push_back(shares[k]);
      continue;
    }
    // The disc's frame from the world axes, not from (u, v): the same disc on
    // a transposed or reparametrised face (the samples are symmetric about e1,
    // so the normal's sign does not matter either).
    const Eigen::Vector3d n = c.tangent_u.cross(c.tangent_v).normalized();
    Eigen::Index axis = 0;
    n.cwiseAbs().minCoeff(&axis);
    const Eigen::Vector3d e1 = (Eigen::Vector3d::Unit(axis) - n[axis] * n).normalized();
    const Eigen::Vector3d e2 = n.cross(e1);
    const Eigen::Matrix<double, 2, 3> to_uv = metric.inverse() * jacobian.transpose();
    const std::size_t first = points.size();
    double carried = 0.0;
    for (const DiscSample& d : disc_samples()) {
      const Eigen::Vector3d t = radius * (d.offset.x() * e1 + d.offset.y() * e2);
      const Eigen::Vector2d uv = c.uv_a + to_uv * t;
      if (!domain.contains(uv) || (!trim.empty() && !trim.contains(uv))) continue;
      points.push_back(uv);
      weights.push_back(d.weight);
      carried += d.weight;
    }
    if (carried == 0.0) {  // the whole disc off the material: the contact point itself
      points.push_back(c.uv_a);
      weights.push_back(shares[k]);
      continue;
    }
    for (std::size_t i = first; i < points.size(); ++i) weights[i] *= shares[k] / carried;
  }
  return pole_weights_at(s, points, weights);
}

}  // namespace argil
