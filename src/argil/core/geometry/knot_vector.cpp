#include "argil/core/geometry/knot_vector.hpp"

#include <algorithm>
#include <cmath>

#include "argil/core/geometry/detail/validation_message.hpp"

namespace argil {

namespace {

using detail::defect;

/// Degree range and knot count.
Status check_size(int p, Eigen::Index m, const KnotFieldNames& f) {
  if (p < 1 || p > kMaxDegree) {
    return defect(f.degree, " is ", p, ", expected 1 to ", kMaxDegree);
  }
  if (m < 2 * (p + 1)) {
    return defect(f.knots, " has ", m, " values, degree ", p, " needs at least ", 2 * (p + 1));
  }
  return Status::success();
}

/// Each value finite and in range, the sequence non-decreasing.
Status check_values(const Eigen::VectorXd& t, const KnotFieldNames& f) {
  const Eigen::Index m = t.size();
  for (Eigen::Index k = 0; k < m; ++k) {
    if (!std::isfinite(t[k])) {
      return defect(f.knots, "[", k, "] is ", t[k]);
    }
    if (std::abs(t[k]) > kMaxKnotMagnitude) {
      return defect(f.knots, "[", k, "] is ", t[k], ", beyond the supported magnitude ",
                    kMaxKnotMagnitude);
    }
  }
  for (Eigen::Index k = 1; k < m; ++k) {
    if (t[k] < t[k - 1]) {
      return defect(f.knots, "[", k, "] = ", t[k], " is below ", f.knots, "[", k - 1,
                    "] = ", t[k - 1]);
    }
  }
  return Status::success();
}

/// Clamped ends, a non-empty domain, interior multiplicity at most p.
Status check_multiplicities(int p, const Eigen::VectorXd& t, const KnotFieldNames& f) {
  const Eigen::Index m = t.size();
  for (int k = 1; k <= p; ++k) {
    if (t[k] != t[0] || t[m - 1 - k] != t[m - 1]) {
      return defect(f.knots, " is not clamped: the first and last values must each repeat ", p + 1,
                    " times for degree ", p);
    }
  }
  if (!(t[0] < t[m - 1])) {
    return defect(f.knots, " spans an empty domain [", t[0], ", ", t[m - 1], "]");
  }
  // Interior runs: indices p+1 .. m-p-2 hold the interior knots of a clamped vector.
  for (Eigen::Index k = p + 1; k < m - p - 1;) {
    Eigen::Index run = 1;
    while (k + run < m - p - 1 && t[k + run] == t[k]) ++run;
    if (run > p) {
      return defect(f.knots, " value ", t[k], " at index ", k, " repeats ", run, " times, degree ",
                    p, " allows at most ", p);
    }
    k += run;
  }
  return Status::success();
}

/// The domain and every non-empty span long enough to resolve.
Status check_spans(const Eigen::VectorXd& t, const KnotFieldNames& f) {
  const Eigen::Index m = t.size();
  const double domain = t[m - 1] - t[0];
  const double largest = std::max({1.0, std::abs(t[0]), std::abs(t[m - 1])});
  if (domain < kMinSpanRatio * largest) {
    return defect(f.knots, " domain [", t[0], ", ", t[m - 1], "] is shorter than ", kMinSpanRatio,
                  " of its knots' magnitude ", largest);
  }
  for (Eigen::Index k = 1; k < m; ++k) {
    if (t[k] > t[k - 1] && t[k] - t[k - 1] < kMinSpanRatio * domain) {
      return defect(f.knots, " span [", t[k - 1], ", ", t[k], "] (index ", k - 1,
                    ") is shorter than ", kMinSpanRatio, " of the domain length ", domain,
                    ": merge the two knots");
    }
  }
  return Status::success();
}

}  // namespace

Status validate_knots(int degree, const Eigen::VectorXd& knots, const KnotFieldNames& names) {
  Status v = check_size(degree, knots.size(), names);
  if (v.ok()) v = check_values(knots, names);
  if (v.ok()) v = check_multiplicities(degree, knots, names);
  if (v.ok()) v = check_spans(knots, names);
  return v;
}

}  // namespace argil
