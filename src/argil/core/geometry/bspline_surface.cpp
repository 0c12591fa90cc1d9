#include "argil/core/geometry/bspline_surface.hpp"

#include "argil/core/geometry/detail/validation_message.hpp"
#include "argil/core/geometry/knot_vector.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace argil {

const char* to_string(Direction d) { return d == Direction::u ? "u" : "v"; }

using detail::defect;

Status validate(const BSplineSurface& s) {
  for (Direction d : kDirections) {
    const std::string degree_field = std::string("degree_") + to_string(d);
    const std::string knots_field = std::string("knots_") + to_string(d);
    Status v = validate_knots(s.degree_in(d), s.knots_in(d), {degree_field, knots_field});
    if (!v.ok()) return v;
  }
  const Eigen::Index n = static_cast<Eigen::Index>(s.count(Direction::u)) * s.count(Direction::v);
  if (s.control_points.rows() != n) {
    return defect("control_points has ", s.control_points.rows(), " rows, the knots need ",
                  s.count(Direction::u), " x ", s.count(Direction::v), " = ", n);
  }
  for (Eigen::Index r = 0; r < n; ++r) {
    if (!s.control_points.row(r).allFinite()) {
      return defect("control_points[", r, "] (i = ", r / s.count(Direction::v),
                    ", j = ", r % s.count(Direction::v), ") is not finite");
    }
    if (s.control_points.row(r).cwiseAbs().maxCoeff() > kMaxCoordinate) {
      return defect("control_points[", r, "] (i = ", r / s.count(Direction::v),
                    ", j = ", r % s.count(Direction::v), ") has a coordinate beyond the supported ",
                    kMaxCoordinate, " mm");
    }
  }
  return detail::validate_weights(s.weights, n);
}

Eigen::VectorXd greville_abscissae(int degree, const Eigen::VectorXd& knots) {
  const Eigen::Index n = knots.size() - degree - 1;
  Eigen::VectorXd xi(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    xi[i] = knots.segment(i + 1, degree).sum() / degree;
  }
  // The sum can round past the ends; the ends are exact by definition.
  xi[0] = knots[degree];
  xi[n - 1] = knots[n];
  for (Eigen::Index i = 1; i < n; ++i) xi[i] = std::min(std::max(xi[i], xi[i - 1]), knots[n]);
  return xi;
}

Box3 control_point_box(const BSplineSurface& s) {
  return {s.control_points.colwise().minCoeff().transpose(),
          s.control_points.colwise().maxCoeff().transpose()};
}

Eigen::MatrixX4d homogeneous_control_points(const BSplineSurface& s) {
  Eigen::MatrixX4d pw(s.control_points.rows(), 4);
  if (s.is_rational()) {
    pw.leftCols<3>() = s.control_points.array().colwise() * s.weights.array();
    pw.col(3) = s.weights;
  } else {
    pw.leftCols<3>() = s.control_points;
    pw.col(3).setOnes();
  }
  return pw;
}

BSplineSurface with_homogeneous_control_points(BSplineSurface s, const Eigen::MatrixX4d& pw,
                                               bool rational) {
  if (rational) {
    s.weights = pw.col(3);
    s.control_points = pw.leftCols<3>().array().colwise() / pw.col(3).array();
  } else {
    s.weights.resize(0);
    s.control_points = pw.leftCols<3>();
  }
  return s;
}

}  // namespace argil
