#include "argil/core/banded_cholesky.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace argil {

Result<BandedCholesky> BandedCholesky::factorize(SymmetricBandMatrix a) {
  const int n = a.size();
  const int b = a.bandwidth();
  for (int i = 0; i < n; ++i) {
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
        std::ostringstream m;
        m.precision(17);
        m << "banded Cholesky: pivot " << i << " of " << n << " is " << sum << " against diagonal "
          << diagonal << ": the matrix is not positive definite to working precision";
        return Status::error(StatusCode::numerical_failure, m.str());
      }
      a.at(i, i) = std::sqrt(sum);
    }
  }
  BandedCholesky out;
  out.l_ = std::move(a);
  return out;
}

void BandedCholesky::solve_in_place(RowMajorMatrix& x) const {
  const int n = l_.size();
  const int b = l_.bandwidth();
  const Eigen::Index c = x.cols();
  assert(x.rows() == n);
  double* data = x.data();
  // L y = b, row by row.
  for (int i = 0; i < n; ++i) {
    double* xi = data + static_cast<Eigen::Index>(i) * c;
    for (int k = std::max(0, i - b); k < i; ++k) {
      const double l = l_.at(i, k);
      const double* xk = data + static_cast<Eigen::Index>(k) * c;
      for (Eigen::Index col = 0; col < c; ++col) xi[col] -= l * xk[col];
    }
    const double inverse = 1.0 / l_.at(i, i);
    for (Eigen::Index col = 0; col < c; ++col) xi[col] *= inverse;
  }
  // L^T x = y, backwards; row i of L scatters into the rows above it.
  for (int i = n - 1; i >= 0; --i) {
    double* xi = data + static_cast<Eigen::Index>(i) * c;
    const double inverse = 1.0 / l_.at(i, i);
    for (Eigen::Index col = 0; col < c; ++col) xi[col] *= inverse;
    for (int k = std::max(0, i - b); k < i; ++k) {
      const double l = l_.at(i, k);
      double* xk = data + static_cast<Eigen::Index>(k) * c;
      for (Eigen::Index col = 0; col < c; ++col) xk[col] -= l * xi[col];
    }
  }
}

}  // namespace argil
