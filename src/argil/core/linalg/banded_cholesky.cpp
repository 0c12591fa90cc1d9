#include "argil/core/linalg/banded_cholesky.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "argil/core/base/detail/simd_clones.hpp"
#include "argil/core/base/number_text.hpp"

namespace argil {

Result<BandedCholesky> BandedCholesky::factorize(SymmetricBandMatrix a) {
  if (Status s = factorize_rows(a, 0, a.size()); !s.ok()) return s;
  return from_factor(std::move(a));
}

BandedCholesky BandedCholesky::from_factor(SymmetricBandMatrix l) {
  BandedCholesky out;
  out.l_ = std::move(l);
  return out;
}

Status BandedCholesky::factorize_rows(SymmetricBandMatrix& a, int begin, int end) {
  const int n = a.size();
  const int b = a.bandwidth();
  for (int i = begin; i < end; ++i) {
    const int first = std::max(0, i - b);
    for (int j = first; j <= i; ++j) {
      // L(i, j) = (A(i, j) - sum_k L(i, k) L(j, k)) / L(j, j), k over both bands.
      const int k0 = std::max(first, j - b);
      double sum = a.at(i, j);
      for (int k = k0; k < j; ++k) sum -= a.at(i, k) * a.at(j, k);
      if (j < i) {
        a.at(i, j) = sum / a.at(j, j);
        continue;
      }
      const double diagonal = a.at(i, i);  // before elimination: the scale of the pivot
      if (!(sum > diagonal * 64 * std::numeric_limits<double>::epsilon())) {
        return Status::error(StatusCode::numerical_failure,
                             "banded Cholesky: pivot " + std::to_string(i) + " of " +
                                 std::to_string(n) + " is " + number_text(sum) +
                                 " against diagonal " + number_text(diagonal) +
                                 ": the matrix is not positive definite to working precision");
      }
      a.at(i, i) = std::sqrt(sum);
    }
  }
  return Status::success();
}

namespace {

/// The two triangular sweeps with C right-hand sides per row, C fixed so the
/// inner loops unroll and vectorise (across the C columns, so each column's
/// sums keep their order). `l` is row-major band storage of L.
template <int C>
ARGIL_AVX2_CLONES void solve_rows(const double* l, int n, int b, double* x) {
  const int stride = b + 1;
  for (int i = 0; i < n; ++i) {                                           // L y = b
    const double* row = l + static_cast<std::ptrdiff_t>(i) * stride + b;  // row[k - i] = L(i, k)
    // Two partial sums (even and odd k) halve the chain of dependent subtractions.
    double acc[C], odd[C];
    for (int c = 0; c < C; ++c) acc[c] = x[i * C + c], odd[c] = 0.0;
    int k = std::max(0, i - b);
    for (; k + 1 < i; k += 2) {
      const double v = row[k - i], w = row[k + 1 - i];
      for (int c = 0; c < C; ++c) {
        acc[c] -= v * x[k * C + c];
        odd[c] -= w * x[(k + 1) * C + c];
      }
    }
    if (k < i)
      for (int c = 0; c < C; ++c) acc[c] -= row[k - i] * x[k * C + c];
    const double inverse = 1.0 / row[0];
    for (int c = 0; c < C; ++c) x[i * C + c] = (acc[c] + odd[c]) * inverse;
  }
  for (int i = n - 1; i >= 0; --i) {  // L^T x = y: row i of L scatters upwards
    const double* row = l + static_cast<std::ptrdiff_t>(i) * stride + b;
    const double inverse = 1.0 / row[0];
    double xi[C];
    for (int c = 0; c < C; ++c) xi[c] = (x[i * C + c] *= inverse);
    for (int k = std::max(0, i - b); k < i; ++k) {
      const double v = row[k - i];
      for (int c = 0; c < C; ++c) x[k * C + c] -= v * xi[c];
    }
  }
}

}  // namespace

void BandedCholesky::solve_in_place(RowMajorMatrix& x) const {
  const int n = l_.size();
  const int b = l_.bandwidth();
  assert(x.rows() == n);
  const double* l = l_.lower_.data();
  switch (x.cols()) {
    case 1:
      return solve_rows<1>(l, n, b, x.data());
    case 3:
      return solve_rows<3>(l, n, b, x.data());
    case 4:
      return solve_rows<4>(l, n, b, x.data());
    default:
      for (Eigen::Index c = 0; c < x.cols(); ++c) {
        Eigen::VectorXd column = x.col(c);
        solve_rows<1>(l, n, b, column.data());
        x.col(c) = column;
      }
  }
}

}  // namespace argil
