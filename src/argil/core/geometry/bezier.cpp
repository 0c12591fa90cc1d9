#include "argil/core/geometry/bezier.hpp"
#include <array>
#include <cmath>

#include "argil/core/geometry/basis.hpp"
#include "argil/core/geometry/detail/homogeneous_derivatives.hpp"
#include "argil/core/geometry/knot_insertion.hpp"

namespace argil {

namespace {

int count_equal(const Eigen::VectorXd& knots, double t) { return knot_multiplicity(knots, t); }

int last_index_of(const Eigen::VectorXd& knots, double t) {
  for (Eigen::Index k = knots.size() - 1; k >= 0; --k) {
    if (knots[k] == t) return static_cast<int>(k);
  }
  return -1;
}

/// Operator of span s: insert both span ends to multiplicity p into the local
/// knot vector U[s-p .. s+p+1] refining the identity "points".
Eigen::MatrixXd span_operator(int p, const Eigen::VectorXd& U, int s) {
  BSplineCurve local{p, U.segment(s - p, 2 * p + 2), Eigen::MatrixXd::Identity(p + 1, p + 1), {}};
  const double a = U[s];
  const double b = U[s + 1];
  const int missing_a = p - count_equal(local.knots, a);
  if (missing_a > 0) local = insert_knot(local, a, missing_a);
  const int missing_b = p - count_equal(local.knots, b);
  if (missing_b > 0) local = insert_knot(local, b, missing_b);
  const int k = last_index_of(local.knots, a);
  return local.points.middleRows(k - p, p + 1);
}

}  // namespace

BezierExtraction bezier_extraction(int degree, const Eigen::VectorXd& knots) {
  BezierExtraction out;
  const int count = static_cast<int>(knots.size()) - degree - 1;
  for (int s = degree; s < count; ++s) {
    if (knots[s] < knots[s + 1]) {
      out.spans.push_back(s);
      out.operators.push_back(span_operator(degree, knots, s));
    }
  }
  return out;
}

SubdivisionMatrices subdivision_matrices(int p) {
  // Binomial coefficients C(i, j) by Pascal's rule, exact in double up to p ~ 50.
  Eigen::MatrixXd binomial = Eigen::MatrixXd::Zero(p + 1, p + 1);
  for (int i = 0; i <= p; ++i) {
    binomial(i, 0) = 1.0;
    for (int j = 1; j <= i; ++j)
      binomial(i, j) = binomial(i - 1, j - 1) + (j < i ? binomial(i - 1, j) : 0.0);
  }
  SubdivisionMatrices m{Eigen::MatrixXd::Zero(p + 1, p + 1), Eigen::MatrixXd::Zero(p + 1, p + 1)};
  for (int i = 0; i <= p; ++i) {
    const double left_scale = std::ldexp(1.0, -i);
    const double right_scale = std::ldexp(1.0, -(p - i));
    for (int j = 0; j <= i; ++j) m.left(i, j) = binomial(i, j) * left_scale;
    for (int j = i; j <= p; ++j) m.right(i, j) = binomial(p - i, j - i) * right_scale;
  }
  return m;
}

Eigen::Vector3d evaluate(const BezierPatch& patch, double s, double t) {
  const Eigen::VectorXd bu = bernstein(patch.degree_u, s);
  const Eigen::VectorXd bv = bernstein(patch.degree_v, t);
  Eigen::Vector4d h = Eigen::Vector4d::Zero();
  for (int a = 0; a <= patch.degree_u; ++a) {
    for (int b = 0; b <= patch.degree_v; ++b) {
      h += bu[a] * bv[b] * patch.points.row(a * (patch.degree_v + 1) + b).transpose();
    }
  }
  return h.head<3>() / h[3];
}

namespace {

/// A degree the compiler knows (the low ones most CAD faces have, whose
/// loops it then unrolls), or kAnyDegree: the patch's own, read at run time.
constexpr int kAnyDegree = -1;

constexpr std::size_t row_size(int degree) {
  return static_cast<std::size_t>(degree == kAnyDegree ? kMaxDegree : degree) + 1;
}

/// Bernstein polynomials of degree P (or `degree`) at t and their first and
/// second derivatives: d/dt B_i^p = p (B_{i-1}^{p-1} - B_i^{p-1}), and the
/// same again for the second derivative from degree p - 2. Only entries 0 to
/// p are set (rows sized for kMaxDegree, when the degree is known only at run
/// time, cost more to clear than to fill).
template <int P>
struct BernsteinRows {
  std::array<double, row_size(P)> value, d1, d2;
};

template <int P>
BernsteinRows<P> bernstein_rows(int runtime_degree, double t, int order) {
  const int p = P == kAnyDegree ? runtime_degree : P;
  // One recurrence (as bernstein()); the derivatives are taken from the rows
  // of degree p - 2 and p - 1 as the recurrence passes them.
  BernsteinRows<P> r;
  std::array<double, row_size(P)>& b = r.value;
  // Entry i of the row b holds, of degree `degree`: zero outside 0 to degree.
  const auto at = [&b](int degree, int i) {
    return i < 0 || i > degree ? 0.0 : b[static_cast<std::size_t>(i)];
  };
  if (order >= 1 && p < 1) r.d1[0] = 0.0;
  if (order >= 2 && p < 2)
    for (int i = 0; i <= p; ++i) r.d2[static_cast<std::size_t>(i)] = 0.0;
  b[0] = 1.0;
  const double s = 1.0 - t;
  for (int j = 1; j <= p; ++j) {
    // b holds the row of degree j - 1 (entries 0 to j - 1).
    if (order >= 2 && j == p - 1) {
      for (int i = 0; i <= p; ++i)
        r.d2[static_cast<std::size_t>(i)] =
            p * (p - 1) * (at(j - 1, i - 2) - 2.0 * at(j - 1, i - 1) + at(j - 1, i));
    }
    if (order >= 1 && j == p) {
      for (int i = 0; i <= p; ++i)
        r.d1[static_cast<std::size_t>(i)] = p * (at(j - 1, i - 1) - at(j - 1, i));
    }
    double saved = 0.0;
    for (int k = 0; k < j; ++k) {
      const double temp = b[static_cast<std::size_t>(k)];
      b[static_cast<std::size_t>(k)] = saved + s * temp;
      saved = t * temp;
    }
    b[static_cast<std::size_t>(j)] = saved;
  }
  return r;
}

/// evaluate_derivatives of a patch of degree P x Q (or its own degrees).
template <int P, int Q>
SurfaceDerivatives patch_derivatives(const BezierPatch& patch, double s, double t, int order) {
  const int p = P == kAnyDegree ? patch.degree_u : P;
  const int q = Q == kAnyDegree ? patch.degree_v : Q;
  const BernsteinRows<P> bu = bernstein_rows<P>(p, s, order);
  const BernsteinRows<Q> bv = bernstein_rows<Q>(q, t, order);
  detail::HomogeneousDerivatives h;
  for (int a = 0; a <= p; ++a) {
    // Sums along v first: the net row a against the v rows.
    Eigen::Vector4d r0 = Eigen::Vector4d::Zero(), r1 = r0, r2 = r0;
    for (int b = 0; b <= q; ++b) {
      const Eigen::Vector4d x = patch.points.row(a * (q + 1) + b).transpose();
      const std::size_t jb = static_cast<std::size_t>(b);
      r0 += bv.value[jb] * x;
      if (order >= 1) r1 += bv.d1[jb] * x;
      if (order >= 2) r2 += bv.d2[jb] * x;
    }
    const std::size_t ia = static_cast<std::size_t>(a);
    h.a00 += bu.value[ia] * r0;
    if (order >= 1) {
      h.a10 += bu.d1[ia] * r0;
      h.a01 += bu.value[ia] * r1;
    }
    if (order >= 2) {
      h.a20 += bu.d2[ia] * r0;
      h.a11 += bu.d1[ia] * r1;
      h.a02 += bu.value[ia] * r2;
    }
  }
  return detail::cartesian(h, order);
}

}  // namespace

SurfaceDerivatives evaluate_derivatives(const BezierPatch& patch, double s, double t, int order) {
  // Degrees 1 to 3 each way through loops the compiler unrolls: the same
  // sums in the same order, so the same bits (as long as the compiler fuses
  // no multiply-adds, as on x86-64 without -march), in about half the time.
  using Evaluate = SurfaceDerivatives (*)(const BezierPatch&, double, double, int);
  static constexpr Evaluate kLow[3][3] = {
      {patch_derivatives<1, 1>, patch_derivatives<1, 2>, patch_derivatives<1, 3>},
      {patch_derivatives<2, 1>, patch_derivatives<2, 2>, patch_derivatives<2, 3>},
      {patch_derivatives<3, 1>, patch_derivatives<3, 2>, patch_derivatives<3, 3>}};
  const int p = patch.degree_u, q = patch.degree_v;
  if (p >= 1 && p <= 3 && q >= 1 && q <= 3) return kLow[p - 1][q - 1](patch, s, t, order);
  return patch_derivatives<kAnyDegree, kAnyDegree>(patch, s, t, order);
}

namespace {

/// Rows (line * across + k * along) of `out` = sum over i of m(k, i) times
/// row (line * across + i * along) of `in`: each line of the net along d
/// mapped by m. Each row of m is read once for its nonzero range (the de
/// Casteljau halves are triangular), not once per line; the sum runs in
/// increasing i, so every caller rounds alike.
template <int P, int Q>
void map_lines_of(const double* in, double* out, int runtime_degree_u, int runtime_degree_v,
                  Direction d, const Eigen::MatrixXd& m) {
  const int degree_u = P == kAnyDegree ? runtime_degree_u : P;
  const int degree_v = Q == kAnyDegree ? runtime_degree_v : Q;
  const int q1 = degree_v + 1;
  const bool in_u = d == Direction::u;
  const int count_along = in_u ? degree_u + 1 : q1;
  const int count_across = in_u ? q1 : degree_u + 1;
  const int along = in_u ? q1 : 1;
  const int across = in_u ? 1 : q1;
  // Nonzero range of row k, inclusive; entries past count_along stay unset
  // (clearing both whole arrays cost a tenth of the mapping on cubic nets).
  std::array<int, kMaxDegree + 1> first, last;
  for (int k = 0; k < count_along; ++k) {
    int lo = 0, hi = count_along - 1;
    while (lo < hi && m(k, lo) == 0.0) ++lo;
    while (hi > lo && m(k, hi) == 0.0) --hi;
    first[static_cast<std::size_t>(k)] = lo;
    last[static_cast<std::size_t>(k)] = hi;
  }
  for (int line = 0; line < count_across; ++line) {
    const double* line_in = in + 4 * line * across;
    double* line_out = out + 4 * line * across;
    for (int k = 0; k < count_along; ++k) {
      Eigen::Vector4d sum = Eigen::Vector4d::Zero();
      for (int i = first[static_cast<std::size_t>(k)]; i <= last[static_cast<std::size_t>(k)]; ++i)
        sum += m(k, i) * Eigen::Map<const Eigen::Vector4d>(line_in + 4 * i * along);
      Eigen::Map<Eigen::Vector4d>(line_out + 4 * k * along) = sum;
    }
  }
}

/// map_lines_of with degrees 1 to 3 each way known to the compiler (see
/// evaluate_derivatives): the same sums in the same order.
void map_lines(const double* in, double* out, int degree_u, int degree_v, Direction d,
               const Eigen::MatrixXd& m) {
  using Map = void (*)(const double*, double*, int, int, Direction, const Eigen::MatrixXd&);
  static constexpr Map kLow[3][3] = {{map_lines_of<1, 1>, map_lines_of<1, 2>, map_lines_of<1, 3>},
                                     {map_lines_of<2, 1>, map_lines_of<2, 2>, map_lines_of<2, 3>},
                                     {map_lines_of<3, 1>, map_lines_of<3, 2>, map_lines_of<3, 3>}};
  if (degree_u >= 1 && degree_u <= 3 && degree_v >= 1 && degree_v <= 3)
    return kLow[degree_u - 1][degree_v - 1](in, out, degree_u, degree_v, d, m);
  map_lines_of<kAnyDegree, kAnyDegree>(in, out, degree_u, degree_v, d, m);
}

}  // namespace

BezierPatch map_along(const BezierPatch& patch, Direction d, const Eigen::MatrixXd& m) {
  BezierPatch out{patch.degree_u, patch.degree_v, PatchNet(patch.points.rows(), 4)};
  map_lines(patch.points.data(), out.points.data(), patch.degree_u, patch.degree_v, d, m);
  return out;
}

void subdivide_into(const BezierPatch& patch, const SubdivisionMatrices& su,
                    const SubdivisionMatrices& sv, const PatchHalves& which, BezierPatch& child) {
  const auto half = [](const SubdivisionMatrices& s, int h) -> const Eigen::MatrixXd& {
    return h == 0 ? s.left : s.right;
  };
  const int p = patch.degree_u, q = patch.degree_v;
  child.degree_u = p;
  child.degree_v = q;
  child.points.resize(patch.points.rows(), 4);
  if (which.u && which.v) {
    // The u split into a buffer on the stack, the v split from it.
    using Buffer = Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::RowMajor,
                                 (kMaxDegree + 1) * (kMaxDegree + 1), 4>;
    Buffer split_u(patch.points.rows(), 4);
    map_lines(patch.points.data(), split_u.data(), p, q, Direction::u, half(su, *which.u));
    map_lines(split_u.data(), child.points.data(), p, q, Direction::v, half(sv, *which.v));
  } else if (which.u) {
    map_lines(patch.points.data(), child.points.data(), p, q, Direction::u, half(su, *which.u));
  } else if (which.v) {
    map_lines(patch.points.data(), child.points.data(), p, q, Direction::v, half(sv, *which.v));
  } else {
    child.points = patch.points;
  }
}

BezierPatch subdivide(const BezierPatch& patch, const SubdivisionMatrices& su,
                      const SubdivisionMatrices& sv, const PatchHalves& which) {
  BezierPatch child;
  subdivide_into(patch, su, sv, which, child);
  return child;
}

}  // namespace argil
