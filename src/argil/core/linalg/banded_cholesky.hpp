#pragma once
// Cholesky factorisation A = L L^T of a symmetric positive definite band
// matrix, for the implicit mass-spring step: factorised once per time step
// size, then two triangular band solves per tick.

#include <Eigen/Core>
#include <vector>

#include "argil/core/base/status.hpp"

namespace argil {

/// Row-major right-hand sides: one row per unknown, one column per system.
using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// Lower half of a symmetric band matrix: entry (i, j) for i - bandwidth <= j <= i.
class SymmetricBandMatrix {
 public:
  SymmetricBandMatrix() = default;
  SymmetricBandMatrix(int size, int bandwidth)
      : size_(size),
        bandwidth_(bandwidth),
        lower_(static_cast<std::size_t>(size) * static_cast<std::size_t>(bandwidth + 1), 0.0) {}
  int size() const { return size_; }
  int bandwidth() const { return bandwidth_; }
  /// Entry (i, j) with j <= i <= j + bandwidth.
  double& at(int i, int j) { return lower_[index(i, j)]; }
  double at(int i, int j) const { return lower_[index(i, j)]; }

 private:
  friend class BandedCholesky;
  std::size_t index(int i, int j) const {
    return static_cast<std::size_t>(i) * static_cast<std::size_t>(bandwidth_ + 1) +
           static_cast<std::size_t>(j - i + bandwidth_);
  }
  int size_ = 0;
  int bandwidth_ = 0;
  std::vector<double> lower_;
};

class BandedCholesky {
 public:
  /// Factorises `a` in O(n b^2); fails with numerical_failure when a pivot is
  /// not positive relative to the diagonal (the matrix is not positive definite
  /// to working precision), naming the row.
  static Result<BandedCholesky> factorize(SymmetricBandMatrix a);
  /// Factorises rows [begin, end) of `a` in place, rows before `begin`
  /// already factorised: a factorisation spread over several calls (row i
  /// costs about bandwidth^2 / 2 multiply-adds) gives the same L to the bit.
  static Status factorize_rows(SymmetricBandMatrix& a, int begin, int end);
  /// The factor of a matrix whose every row factorize_rows has factorised.
  static BandedCholesky from_factor(SymmetricBandMatrix l);

  int size() const { return l_.size(); }
  /// Solves A X = B in place in O(n b c) for c columns.
  void solve_in_place(RowMajorMatrix& b) const;

 private:
  SymmetricBandMatrix l_;
};

}  // namespace argil
