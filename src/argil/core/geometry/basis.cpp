#include "argil/core/geometry/basis.hpp"

#include <algorithm>
#include <array>
#include <cassert>

#include "argil/core/geometry/bspline_surface.hpp"

namespace argil {

int find_span(int degree, const Eigen::VectorXd& knots, int count, double t) {
  const int n = count - 1;
  if (t >= knots[n + 1]) {
    // Last non-empty span: skip the end knot's run.
    int s = n;
    while (s > degree && knots[s] == knots[n + 1]) --s;
    return s;
  }
  if (t <= knots[degree]) {
    int s = degree;
    while (s < n && knots[s + 1] == knots[degree]) ++s;
    return s;
  }
  int low = degree;
  int high = n + 1;
  while (high - low > 1) {  // invariant: knots[low] <= t < knots[high]
    const int mid = (low + high) / 2;
    if (t < knots[mid]) {
      high = mid;
    } else {
      low = mid;
    }
  }
  return low;
}

int knot_multiplicity(const Eigen::VectorXd& knots, double t) {
  int m = 0;
  for (Eigen::Index k = 0; k < knots.size(); ++k) m += knots[k] == t ? 1 : 0;
  return m;
}

void basis_derivatives(int p, const Eigen::VectorXd& U, int span, double t, int order,
                       Eigen::Ref<Eigen::MatrixXd> out) {
  assert(p >= 1 && p <= kMaxDegree);
  assert(out.rows() == order + 1 && out.cols() == p + 1);
  constexpr int kN = kMaxDegree + 1;
  std::array<std::array<double, kN>, kN>
      ndu;  // basis values and knot differences (no zero fill: hot path)
  std::array<double, kN> left;
  std::array<double, kN> right;
  ndu[0][0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = t - U[span + 1 - j];
    right[j] = U[span + j] - t;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      ndu[j][r] = right[r + 1] + left[j - r];  // lower triangle: knot differences
      const double temp = ndu[r][j - 1] / ndu[j][r];
      ndu[r][j] = saved + right[r + 1] * temp;  // upper triangle: basis functions
      saved = left[j - r] * temp;
    }
    ndu[j][j] = saved;
  }
  for (int j = 0; j <= p; ++j) out(0, j) = ndu[j][p];
  // Derivatives above the degree vanish; the recurrence below needs k <= p.
  const int top = std::min(order, p);
  for (int k = top + 1; k <= order; ++k) out.row(k).setZero();
  if (top == 0) return;
  if (top == 1) {
    // First derivatives alone (most callers): the recurrence below for k = 1,
    // p (N_{r-1,p-1} / (u_{r+p} - u_r) - N_{r,p-1} / (u_{r+p+1} - u_{r+1})),
    // with each knot difference's reciprocal taken once for both neighbours
    // (-(1 / x) is -1 / x to the bit, so the values are the recurrence's).
    std::array<double, kN> inverse;
    for (int r = 0; r < p; ++r) inverse[r] = 1.0 / ndu[p][r];
    for (int r = 0; r <= p; ++r) {
      double d = r >= 1 ? inverse[r - 1] * ndu[r - 1][p - 1] : 0.0;
      if (r < p) d += -inverse[r] * ndu[r][p - 1];
      out(1, r) = d * p;
    }
    return;
  }

  std::array<std::array<double, kN>, 2> a;
  for (int r = 0; r <= p; ++r) {
    int s1 = 0;
    int s2 = 1;
    a[0][0] = 1.0;
    for (int k = 1; k <= top; ++k) {
      double d = 0.0;
      const int rk = r - k;
      const int pk = p - k;
      if (r >= k) {
        a[s2][0] = a[s1][0] / ndu[pk + 1][rk];
        d = a[s2][0] * ndu[rk][pk];
      }
      const int j1 = rk >= -1 ? 1 : -rk;
      const int j2 = (r - 1 <= pk) ? k - 1 : p - r;
      for (int j = j1; j <= j2; ++j) {
        a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][rk + j];
        d += a[s2][j] * ndu[rk + j][pk];
      }
      if (r <= pk) {
        a[s2][k] = -a[s1][k - 1] / ndu[pk + 1][r];
        d += a[s2][k] * ndu[r][pk];
      }
      out(k, r) = d;
      std::swap(s1, s2);
    }
  }
  double factor = p;
  for (int k = 1; k <= top; ++k) {
    for (int j = 0; j <= p; ++j) out(k, j) *= factor;
    factor *= (p - k);
  }
}

Eigen::MatrixXd basis_derivatives(int degree, const Eigen::VectorXd& knots, int span, double t,
                                  int order) {
  Eigen::MatrixXd out(order + 1, degree + 1);
  basis_derivatives(degree, knots, span, t, order, out);
  return out;
}

Eigen::VectorXd bernstein(int degree, double t) {
  // de Casteljau-style recurrence, stable on [0, 1] (The NURBS Book A1.3).
  Eigen::VectorXd b = Eigen::VectorXd::Zero(degree + 1);
  b[0] = 1.0;
  const double s = 1.0 - t;
  for (int j = 1; j <= degree; ++j) {
    double saved = 0.0;
    for (int k = 0; k < j; ++k) {
      const double temp = b[k];
      b[k] = saved + s * temp;
      saved = t * temp;
    }
    b[j] = saved;
  }
  return b;
}

}  // namespace argil
