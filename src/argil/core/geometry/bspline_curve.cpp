#include "argil/core/geometry/bspline_curve.hpp"

#include <algorithm>
#include <cmath>

#include "argil/core/geometry/basis.hpp"
#include "argil/core/geometry/detail/validation_message.hpp"
#include "argil/core/geometry/knot_vector.hpp"

namespace argil {

using detail::defect;

Status validate(const BSplineCurve& c) {
  const Status knots = validate_knots(c.degree, c.knots);
  if (!knots.ok()) return knots;
  const Eigen::Index n = c.count();
  if (c.points.rows() != n) {
    return defect("points has ", c.points.rows(), " rows, the knots need ", n);
  }
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!c.points.row(i).allFinite()) {
      return defect("points[", i, "] is not finite");
    }
  }
  return detail::validate_weights(c.weights, n);
}

Eigen::VectorXd evaluate(const BSplineCurve& c, double t) {
  const int n = c.count();
  const double t_clamped = std::clamp(t, c.domain_start(), c.domain_end());
  const int span = find_span(c.degree, c.knots, n, t_clamped);
  const Eigen::MatrixXd basis = basis_derivatives(c.degree, c.knots, span, t_clamped, 0);
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(c.points.cols());
  double weight_sum = 0.0;
  for (int r = 0; r <= c.degree; ++r) {
    const Eigen::Index i = span - c.degree + r;
    const double w = c.is_rational() ? c.weights[i] : 1.0;
    sum += basis(0, r) * w * c.points.row(i).transpose();
    weight_sum += basis(0, r) * w;
  }
  return sum / weight_sum;
}

}  // namespace argil
