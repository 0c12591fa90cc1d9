#include "argil/core/linalg/banded_lu.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "argil/core/base/number_text.hpp"

namespace argil {

Result<BandedLU> BandedLU::factorize(BandedMatrix a) {
  const int n = a.size;
  const double norm = a.norm1();
  const double tiny = norm * std::numeric_limits<double>::epsilon() * n;
  for (int k = 0; k < n; ++k) {
    const double pivot = a.at(k, k);
    if (!(std::abs(pivot) > tiny)) {
      return Status::error(StatusCode::numerical_failure,
                           "banded LU: pivot " + std::to_string(k) + " of " + std::to_string(n) +
                               " is " + number_text(pivot) + " (matrix 1-norm " +
                               number_text(norm) +
                               "): the matrix is singular to working precision");
    }
    const int last_row = std::min(n - 1, k + a.lower);
    const int last_col = std::min(n - 1, k + a.upper);
    for (int i = k + 1; i <= last_row; ++i) {
      const double factor = (a.at(i, k) /= pivot);
      if (factor == 0.0) continue;
      for (int j = k + 1; j <= last_col; ++j) a.at(i, j) -= factor * a.at(k, j);
    }
  }
  BandedLU lu;
  lu.lu_ = std::move(a);
  // ||A^-1||_1 is the largest column sum of A^-1: solve for each unit vector.
  double inverse_norm = 0.0;
  Eigen::MatrixXd e(n, 1);
  for (int j = 0; j < n; ++j) {
    e.setZero();
    e(j, 0) = 1.0;
    lu.solve_in_place(e);
    inverse_norm = std::max(inverse_norm, e.cwiseAbs().sum());
  }
  lu.condition_ = norm * inverse_norm;
  return lu;
}

void BandedLU::solve_in_place(Eigen::Ref<Eigen::MatrixXd> b) const {
  const int n = lu_.size;
  for (int k = 0; k < n; ++k) {  // L y = b, unit diagonal
    const int last_row = std::min(n - 1, k + lu_.lower);
    for (int i = k + 1; i <= last_row; ++i) {
      const double factor = lu_.band(lu_.upper + i - k, k);
      if (factor != 0.0) b.row(i) -= factor * b.row(k);
    }
  }
  for (int k = n - 1; k >= 0; --k) {  // U x = y
    b.row(k) /= lu_.band(lu_.upper, k);
    const int first_row = std::max(0, k - lu_.upper);
    for (int i = first_row; i < k; ++i) {
      const double factor = lu_.band(lu_.upper + i - k, k);
      if (factor != 0.0) b.row(i) -= factor * b.row(k);
    }
  }
}

void BandedLU::solve_transpose_in_place(Eigen::Ref<Eigen::MatrixXd> b) const {
  const int n = lu_.size;
  for (int k = 0; k < n; ++k) {  // U^T y = b: row k of U^T is column k of U
    const int first_row = std::max(0, k - lu_.upper);
    for (int i = first_row; i < k; ++i) {
      const double factor = lu_.band(lu_.upper + i - k, k);
      if (factor != 0.0) b.row(k) -= factor * b.row(i);
    }
    b.row(k) /= lu_.band(lu_.upper, k);
  }
  for (int k = n - 1; k >= 0; --k) {  // L^T x = y, unit diagonal
    const int last_row = std::min(n - 1, k + lu_.lower);
    for (int i = k + 1; i <= last_row; ++i) {
      const double factor = lu_.band(lu_.upper + i - k, k);
      if (factor != 0.0) b.row(k) -= factor * b.row(i);
    }
  }
}

}  // namespace argil
