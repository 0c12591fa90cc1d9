#include "argil/core/geometry/bspline_surface.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <type_traits>

#include "argil/core/base/number_text.hpp"

namespace argil {

const char* to_string(Direction d) { return d == Direction::u ? "u" : "v"; }

const char* to_string(SurfaceDefect defect) {
  switch (defect) {
    case SurfaceDefect::none:
      return "none";
    case SurfaceDefect::degree_out_of_range:
      return "degree_out_of_range";
    case SurfaceDefect::too_few_knots:
      return "too_few_knots";
    case SurfaceDefect::non_finite_knot:
      return "non_finite_knot";
    case SurfaceDefect::knots_decreasing:
      return "knots_decreasing";
    case SurfaceDefect::knots_not_clamped:
      return "knots_not_clamped";
    case SurfaceDefect::multiplicity_too_high:
      return "multiplicity_too_high";
    case SurfaceDefect::empty_domain:
      return "empty_domain";
    case SurfaceDefect::knot_out_of_range:
      return "knot_out_of_range";
    case SurfaceDefect::span_too_short:
      return "span_too_short";
    case SurfaceDefect::control_point_count:
      return "control_point_count";
    case SurfaceDefect::non_finite_control_point:
      return "non_finite_control_point";
    case SurfaceDefect::control_point_out_of_range:
      return "control_point_out_of_range";
    case SurfaceDefect::weight_count:
      return "weight_count";
    case SurfaceDefect::non_finite_weight:
      return "non_finite_weight";
    case SurfaceDefect::non_positive_weight:
      return "non_positive_weight";
    case SurfaceDefect::weight_out_of_range:
      return "weight_out_of_range";
  }
  return "unknown";
}

namespace {

/// A part of a defect's text; numbers print as number_text, exact and short.
template <class Part>
void append_part(std::ostringstream& text, const Part& part) {
  if constexpr (std::is_floating_point_v<Part>) {
    text << number_text(static_cast<double>(part));
  } else {
    text << part;
  }
}

template <class... Parts>
SurfaceValidation defect(SurfaceDefect d, const Parts&... parts) {
  std::ostringstream text;
  (append_part(text, parts), ...);
  return {d, text.str()};
}

SurfaceValidation validate_knots(const BSplineSurface& s, Direction d) {
  const char* dir = to_string(d);
  const int p = s.degree_in(d);
  const Eigen::VectorXd& t = s.knots_in(d);
  const Eigen::Index m = t.size();
  if (p < 1 || p > kMaxDegree) {
    return defect(SurfaceDefect::degree_out_of_range, "degree_", dir, " is ", p, ", expected 1 to ",
                  kMaxDegree);
  }
  if (m < 2 * (p + 1)) {
    return defect(SurfaceDefect::too_few_knots, "knots_", dir, " has ", m, " values, degree ", p,
                  " needs at least ", 2 * (p + 1));
  }
  for (Eigen::Index k = 0; k < m; ++k) {
    if (!std::isfinite(t[k])) {
      return defect(SurfaceDefect::non_finite_knot, "knots_", dir, "[", k, "] is ", t[k]);
    }
    if (std::abs(t[k]) > kMaxKnotMagnitude) {
      return defect(SurfaceDefect::knot_out_of_range, "knots_", dir, "[", k, "] is ", t[k],
                    ", beyond the supported magnitude ", kMaxKnotMagnitude);
    }
  }
  for (Eigen::Index k = 1; k < m; ++k) {
    if (t[k] < t[k - 1]) {
      return defect(SurfaceDefect::knots_decreasing, "knots_", dir, "[", k, "] = ", t[k],
                    " is below knots_", dir, "[", k - 1, "] = ", t[k - 1]);
    }
  }
  for (int k = 1; k <= p; ++k) {
    if (t[k] != t[0] || t[m - 1 - k] != t[m - 1]) {
      return defect(SurfaceDefect::knots_not_clamped, "knots_", dir,
                    " is not clamped: the first and last values must each repeat ", p + 1,
                    " times for degree ", p);
    }
  }
  if (!(t[0] < t[m - 1])) {
    return defect(SurfaceDefect::empty_domain, "knots_", dir, " spans an empty domain [", t[0],
                  ", ", t[m - 1], "]");
  }
  // Interior runs: indices p+1 .. m-p-2 hold the interior knots of a clamped vector.
  for (Eigen::Index k = p + 1; k < m - p - 1;) {
    Eigen::Index run = 1;
    while (k + run < m - p - 1 && t[k + run] == t[k]) ++run;
    if (run > p) {
      return defect(SurfaceDefect::multiplicity_too_high, "knots_", dir, " value ", t[k],
                    " at index ", k, " repeats ", run, " times, degree ", p, " allows at most ", p);
    }
    k += run;
  }
  const double domain = t[m - 1] - t[0];
  const double largest = std::max({1.0, std::abs(t[0]), std::abs(t[m - 1])});
  if (domain < kMinSpanRatio * largest) {
    return defect(SurfaceDefect::span_too_short, "knots_", dir, " domain [", t[0], ", ", t[m - 1],
                  "] is shorter than ", kMinSpanRatio, " of its knots' magnitude ", largest);
  }
  for (Eigen::Index k = 1; k < m; ++k) {
    if (t[k] > t[k - 1] && t[k] - t[k - 1] < kMinSpanRatio * domain) {
      return defect(SurfaceDefect::span_too_short, "knots_", dir, " span [", t[k - 1], ", ", t[k],
                    "] (index ", k - 1, ") is shorter than ", kMinSpanRatio,
                    " of the domain length ", domain, ": merge the two knots");
    }
  }
  return {};
}

}  // namespace

SurfaceValidation validate(const BSplineSurface& s) {
  for (Direction d : kDirections) {
    SurfaceValidation v = validate_knots(s, d);
    if (!v.ok()) return v;
  }
  const Eigen::Index n = static_cast<Eigen::Index>(s.count(Direction::u)) * s.count(Direction::v);
  if (s.control_points.rows() != n) {
    return defect(SurfaceDefect::control_point_count, "control_points has ",
                  s.control_points.rows(), " rows, the knots need ", s.count(Direction::u), " x ",
                  s.count(Direction::v), " = ", n);
  }
  for (Eigen::Index r = 0; r < n; ++r) {
    if (!s.control_points.row(r).allFinite()) {
      return defect(SurfaceDefect::non_finite_control_point, "control_points[", r,
                    "] (i = ", r / s.count(Direction::v), ", j = ", r % s.count(Direction::v),
                    ") is not finite");
    }
    if (s.control_points.row(r).cwiseAbs().maxCoeff() > kMaxCoordinate) {
      return defect(SurfaceDefect::control_point_out_of_range, "control_points[", r,
                    "] (i = ", r / s.count(Direction::v), ", j = ", r % s.count(Direction::v),
                    ") has a coordinate beyond the supported ", kMaxCoordinate, " mm");
    }
  }
  if (s.weights.size() != 0 && s.weights.size() != n) {
    return defect(SurfaceDefect::weight_count, "weights has ", s.weights.size(),
                  " values, expected 0 or ", n);
  }
  for (Eigen::Index r = 0; r < s.weights.size(); ++r) {
    if (!std::isfinite(s.weights[r])) {
      return defect(SurfaceDefect::non_finite_weight, "weights[", r, "] is ", s.weights[r]);
    }
    if (!(s.weights[r] > 0.0)) {
      return defect(SurfaceDefect::non_positive_weight, "weights[", r, "] is ", s.weights[r],
                    ", weights must be positive");
    }
    if (s.weights[r] > kMaxWeight || s.weights[r] < 1.0 / kMaxWeight) {
      return defect(SurfaceDefect::weight_out_of_range, "weights[", r, "] is ", s.weights[r],
                    ", outside the supported [", 1.0 / kMaxWeight, ", ", kMaxWeight, "]");
    }
  }
  if (s.weights.size() > 0 && s.weights.maxCoeff() > kMaxWeightRatio * s.weights.minCoeff()) {
    return defect(SurfaceDefect::weight_out_of_range, "weights range from ", s.weights.minCoeff(),
                  " to ", s.weights.maxCoeff(), ", a ratio above the supported ", kMaxWeightRatio);
  }
  return {};
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
