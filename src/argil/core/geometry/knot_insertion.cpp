#include "argil/core/geometry/knot_insertion.hpp"

#include <cassert>
#include <string>
#include <utility>

#include "argil/core/base/number_text.hpp"
#include "argil/core/geometry/basis.hpp"

namespace argil {

namespace {

/// Knot insertion on polynomial control points (The NURBS Book A5.1).
BSplineCurve insert_polynomial(const BSplineCurve& c, double t, int times) {
  const int p = c.degree;
  const Eigen::VectorXd& U = c.knots;
  const int m = static_cast<int>(U.size());  // knots: 0 .. m-1
  const int n = m - p - 2;                   // last control point index
  if (times <= 0) return c;
  // Span k with U[k] <= t < U[k+1]; for t equal to a knot, the last copy.
  int k = p;
  while (k + 1 < m - 1 && U[k + 1] <= t) ++k;
  const int s = knot_multiplicity(U, t);
  assert(s + times <= p && "multiplicity would exceed the degree");

  BSplineCurve out;
  out.degree = p;
  out.knots.resize(m + times);
  out.knots.head(k + 1) = U.head(k + 1);
  out.knots.segment(k + 1, times).setConstant(t);
  out.knots.tail(m - k - 1) = U.tail(m - k - 1);

  const Eigen::Index dim = c.points.cols();
  out.points.resize(n + 1 + times, dim);
  for (int i = 0; i <= k - p; ++i) out.points.row(i) = c.points.row(i);
  for (int i = k - s; i <= n; ++i) out.points.row(i + times) = c.points.row(i);
  BSplineCurve::Points r(p - s + 1, dim);
  for (int i = 0; i <= p - s; ++i) r.row(i) = c.points.row(k - p + i);
  int L = k - p;
  for (int j = 1; j <= times; ++j) {
    L = k - p + j;
    for (int i = 0; i <= p - j - s; ++i) {
      const double alpha = (t - U[L + i]) / (U[i + k + 1] - U[L + i]);
      r.row(i) = alpha * r.row(i + 1) + (1.0 - alpha) * r.row(i);
    }
    out.points.row(L) = r.row(0);
    out.points.row(k + times - j - s) = r.row(p - j - s);
  }
  for (int i = L + 1; i < k - s; ++i) out.points.row(i) = r.row(i - L);
  return out;
}

}  // namespace

BSplineCurve insert_knot(const BSplineCurve& c, double t, int times) {
  if (!c.is_rational()) return insert_polynomial(c, t, times);
  const Eigen::Index dim = c.points.cols();
  BSplineCurve homogeneous{c.degree, c.knots, BSplineCurve::Points(c.points.rows(), dim + 1), {}};
  homogeneous.points.leftCols(dim) = c.points.array().colwise() * c.weights.array();
  homogeneous.points.col(dim) = c.weights;
  BSplineCurve out = insert_polynomial(homogeneous, t, times);
  out.weights = out.points.col(dim);
  out.points = (out.points.leftCols(dim).array().colwise() / out.weights.array()).eval();
  return out;
}

Result<BSplineSurface> insert_knot(const BSplineSurface& s, Direction d, double t, int times) {
  const int p = s.degree_in(d);
  const Eigen::VectorXd& U = s.knots_in(d);
  if (!(t > s.domain_start(d) && t < s.domain_end(d))) {
    return Status::error(
        StatusCode::invalid_argument,
        "insert_knot: knot " + number_text(t) + " is outside the open " + to_string(d) +
            " domain " +
            interval_text({s.domain_start(d), s.domain_end(d), IntervalEnds::open}, ""));
  }
  const int existing = knot_multiplicity(U, t);
  if (times < 0 || existing + times > p) {
    return Status::error(StatusCode::invalid_argument,
                         "insert_knot: inserting " + number_text(t) + " " + std::to_string(times) +
                             " times in " + to_string(d) + " gives multiplicity " +
                             std::to_string(existing + times) + ", degree " + std::to_string(p) +
                             " allows " + std::to_string(p));
  }
  const Eigen::MatrixX4d pw = homogeneous_control_points(s);
  const int n_d = s.count(d);
  const int n_o = s.count(other(d));
  auto pole = [&](int along, int across) {
    return d == Direction::u ? s.pole_index(along, across) : s.pole_index(across, along);
  };

  BSplineSurface out = s;
  const int n_new = n_d + times;
  Eigen::MatrixX4d pw_new(static_cast<Eigen::Index>(n_new) * n_o, 4);
  BSplineCurve line{p, U, BSplineCurve::Points(n_d, 4), {}};
  for (int a = 0; a < n_o; ++a) {
    for (int i = 0; i < n_d; ++i) line.points.row(i) = pw.row(pole(i, a));
    const BSplineCurve refined = insert_knot(line, t, times);
    if (a == 0) out.knots[index_of(d)] = refined.knots;
    for (int i = 0; i < n_new; ++i) {
      const Eigen::Index row = d == Direction::u ? static_cast<Eigen::Index>(i) * n_o + a
                                                 : static_cast<Eigen::Index>(a) * n_new + i;
      pw_new.row(row) = refined.points.row(i);
    }
  }
  return with_homogeneous_control_points(std::move(out), pw_new, s.is_rational());
}

}  // namespace argil
