#include "argil/core/geometry/degree_elevation.hpp"

#include <Eigen/LU>
#include <string>

#include "argil/core/geometry/basis.hpp"

namespace argil {

namespace {

/// Knots with every distinct value's multiplicity raised by `times`.
Eigen::VectorXd elevated_knots(const Eigen::VectorXd& t, int times) {
  std::vector<double> out;
  for (Eigen::Index k = 0; k < t.size(); ++k) {
    out.push_back(t[k]);
    if (k + 1 == t.size() || t[k + 1] != t[k])
      for (int r = 0; r < times; ++r) out.push_back(t[k]);
  }
  return Eigen::Map<const Eigen::VectorXd>(out.data(), static_cast<Eigen::Index>(out.size()));
}

/// Row k: the values at x of the `count` basis functions of (degree, knots).
Eigen::MatrixXd basis_matrix(int degree, const Eigen::VectorXd& knots, const Eigen::VectorXd& x) {
  const int count = static_cast<int>(knots.size()) - degree - 1;
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(x.size(), count);
  Eigen::MatrixXd values(1, degree + 1);
  for (Eigen::Index k = 0; k < x.size(); ++k) {
    const int span = find_span(degree, knots, count, x[k]);
    basis_derivatives(degree, knots, span, x[k], 0, values);
    for (int r = 0; r <= degree; ++r) out(k, span - degree + r) = values(0, r);
  }
  return out;
}

}  // namespace

Result<BSplineSurface> elevate_degree(const BSplineSurface& surface, Direction d, int times) {
  const int p = surface.degree_in(d);
  if (times < 0 || p + times > kMaxElevatedDegree) {
    return Status::error(StatusCode::invalid_argument,
                         "degree elevation of " + std::string(to_string(d)) + " by " +
                             std::to_string(times) + ": the degree must stay in [1, " +
                             std::to_string(kMaxElevatedDegree) + "], it is " + std::to_string(p));
  }
  if (times == 0) return surface;
  const Eigen::VectorXd& t = surface.knots_in(d);
  const Eigen::VectorXd raised = elevated_knots(t, times);
  const int q = p + times;
  const Eigen::VectorXd at = greville_abscissae(q, raised);
  // New coefficients = C^-1 B old: B the old basis and C the new one at the
  // new Greville abscissae.
  const Eigen::MatrixXd transfer =
      basis_matrix(q, raised, at).partialPivLu().solve(basis_matrix(p, t, at));
  const Eigen::MatrixX4d pw = homogeneous_control_points(surface);
  const int nu = surface.count(Direction::u), nv = surface.count(Direction::v);
  const int n_new = static_cast<int>(transfer.rows());
  BSplineSurface out = surface;
  out.degree[static_cast<std::size_t>(index_of(d))] = q;
  out.knots[static_cast<std::size_t>(index_of(d))] = raised;
  const int out_u = d == Direction::u ? n_new : nu, out_v = d == Direction::u ? nv : n_new;
  Eigen::MatrixX4d next = Eigen::MatrixX4d::Zero(static_cast<Eigen::Index>(out_u) * out_v, 4);
  for (int a = 0; a < out_u; ++a)
    for (int b = 0; b < out_v; ++b) {
      const int k = d == Direction::u ? a : b;  // new index along d
      for (int i = 0; i < transfer.cols(); ++i) {
        const double c = transfer(k, i);
        if (c == 0.0) continue;
        const Eigen::Index old = d == Direction::u ? static_cast<Eigen::Index>(i) * nv + b
                                                   : static_cast<Eigen::Index>(a) * nv + i;
        next.row(static_cast<Eigen::Index>(a) * out_v + b) += c * pw.row(old);
      }
    }
  out.control_points.resize(next.rows(), 3);
  return with_homogeneous_control_points(out, next, surface.is_rational());
}

}  // namespace argil
