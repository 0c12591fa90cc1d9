#include "argil/core/geometry/bspline_surface.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace argil {

const char* to_string(Direction d) { return d == Direction::u ? "u" : "v"; }

namespace {

template <class... Parts>
Status defect(const Parts&... parts) {
  std::ostringstream text;
  text.precision(17);
  (text << ... << parts);
  return Status::error(StatusCode::invalid_surface, text.str());
}

Status validate_knots(const BSplineSurface& s, Direction d) {
  const char* dir = to_string(d);
  const int p = s.degree_in(d);
  const Eigen::VectorXd& t = s.knots_in(d);
  const Eigen::Index m = t.size();
  if (p < 1 || p > kMaxDegree) {
    return defect("degree_", dir, " is ", p, ", expected 1 to ", kMaxDegree);
  }
  if (m < 2 * (p + 1)) {
    return defect("knots_", dir, " has ", m, " values, degree ", p, " needs at least ",
                  2 * (p + 1));
  }
  for (Eigen::Index k = 0; k < m; ++k) {
    if (!std::isfinite(t[k])) {
      return defect("knots_", dir, "[", k, "] is ", t[k]);
    }
    if (std::abs(t[k]) > kMaxKnotMagnitude) {
      return defect("knots_", dir, "[", k, "] is ", t[k], ", beyond the supported magnitude ",
                    kMaxKnotMagnitude);
    }
  }
  for (Eigen::Index k = 1; k < m; ++k) {
    if (t[k] < t[k - 1]) {
      return defect("knots_", dir, "[", k, "] = ", t[k], " is below knots_", dir, "[", k - 1,
                    "] = ", t[k - 1]);
    }
  }
  for (int k = 1; k <= p; ++k) {
    if (t[k] != t[0] || t[m - 1 - k] != t[m - 1]) {
      return defect("knots_", dir, " is not clamped: the first and last values must each repeat ",
                    p + 1, " times for degree ", p);
    }
  }
  if (!(t[0] < t[m - 1])) {
    return defect("knots_", dir, " spans an empty domain [", t[0], ", ", t[m - 1], "]");
  }
  // Interior runs: indices p+1 .. m-p-2 hold the interior knots of a clamped vector.
  for (Eigen::Index k = p + 1; k < m - p - 1;) {
    Eigen::Index run = 1;
    while (k + run < m - p - 1 && t[k + run] == t[k]) ++run;
    if (run > p) {
      return defect("knots_", dir, " value ", t[k], " at index ", k, " repeats ", run,
                    " times, degree ", p, " allows at most ", p);
    }
    k += run;
  }
  const double domain = t[m - 1] - t[0];
  const double largest = std::max({1.0, std::abs(t[0]), std::abs(t[m - 1])});
  if (domain < kMinSpanRatio * largest) {
    return defect("knots_", dir, " domain [", t[0], ", ", t[m - 1], "] is shorter than ",
                  kMinSpanRatio, " of its knots' magnitude ", largest);
  }
  for (Eigen::Index k = 1; k < m; ++k) {
    if (t[k] > t[k - 1] && t[k] - t[k - 1] < kMinSpanRatio * domain) {
      return defect("knots_", dir, " span [", t[k - 1], ", ", t[k], "] (index ", k - 1,
                    ") is shorter than ", kMinSpanRatio, " of the domain length ", domain,
                    ": merge the two knots");
    }
  }
  return Status::success();
}

}  // namespace

Status validate(const BSplineSurface& s) {
  for (Direction d : kDirections) {
    Status v = validate_knots(s, d);
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
  if (s.weights.size() != 0 && s.weights.size() != n) {
    return defect("weights has ", s.weights.size(), " values, expected 0 or ", n);
  }
  for (Eigen::Index r = 0; r < s.weights.size(); ++r) {
    if (!std::isfinite(s.weights[r])) {
      return defect("weights[", r, "] is ", s.weights[r]);
    }
    if (!(s.weights[r] > 0.0)) {
      return defect("weights[", r, "] is ", s.weights[r], ", weights must be positive");
    }
    if (s.weights[r] > kMaxWeight || s.weights[r] < 1.0 / kMaxWeight) {
      return defect("weights[", r, "] is ", s.weights[r], ", outside the supported [",
                    1.0 / kMaxWeight, ", ", kMaxWeight, "]");
    }
  }
  if (s.weights.size() > 0 && s.weights.maxCoeff() > kMaxWeightRatio * s.weights.minCoeff()) {
    return defect("weights range from ", s.weights.minCoeff(), " to ", s.weights.maxCoeff(),
                  ", a ratio above the supported ", kMaxWeightRatio);
  }
  return Status::success();
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

void set_homogeneous_control_points(BSplineSurface& s, const Eigen::MatrixX4d& pw, bool rational) {
  if (rational) {
    s.weights = pw.col(3);
    s.control_points = pw.leftCols<3>().array().colwise() / pw.col(3).array();
  } else {
    s.weights.resize(0);
    s.control_points = pw.leftCols<3>();
  }
}

}  // namespace argil
