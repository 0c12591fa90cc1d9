#pragma once
// Cholesky factorisation A = L L^T of a symmetric positive definite band
// matrix, for the implicit mass-spring step: factorised once per time step
// size, then two triangular band solves per tick.

#include <Eigen/Core>
#include <algorithm>
#include <memory>
#include <utility>
#include <vector>

#include "argil/core/base/status.hpp"

namespace argil {

/// Row-major right-hand sides: one row per unknown, one column per system.
using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// Allocates without initialising: a large buffer's pages are then first
/// touched where and when it is written, not all at allocation.
template <class T>
struct DefaultInitAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = DefaultInitAllocator<U>;
  };
  using std::allocator<T>::allocator;
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    if constexpr (sizeof...(Args) == 0)
      ::new (static_cast<void*>(p)) U;  // default-initialised: no write for a double
    else
      ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

/// Lower half of a symmetric band matrix: entry (i, j) for i - bandwidth <= j <= i.
class SymmetricBandMatrix {
 public:
  SymmetricBandMatrix() = default;
  /// Every entry zero.
  SymmetricBandMatrix(int size, int bandwidth) : SymmetricBandMatrix(unfilled(size, bandwidth)) {
    std::fill(lower_.begin(), lower_.end(), 0.0);
  }
  /// Storage only: a row's entries are undefined until clear_row. Rows
  /// filled one batch at a time touch the memory one batch at a time (a
  /// fresh page costs several microseconds on some machines).
  static SymmetricBandMatrix unfilled(int size, int bandwidth) {
    SymmetricBandMatrix m;
    m.size_ = size;
    m.bandwidth_ = bandwidth;
    m.lower_.resize(static_cast<std::size_t>(size) * static_cast<std::size_t>(bandwidth + 1));
    return m;
  }
  int size() const { return size_; }
  int bandwidth() const { return bandwidth_; }
  /// Entry (i, j) with j <= i <= j + bandwidth.
  double& at(int i, int j) { return lower_[index(i, j)]; }
  double at(int i, int j) const { return lower_[index(i, j)]; }
  /// Sets row i's entries to zero.
  void clear_row(int i) {
    const auto first = lower_.begin() + static_cast<std::ptrdiff_t>(index(i, i - bandwidth_));
    std::fill(first, first + bandwidth_ + 1, 0.0);
  }

 private:
  friend class BandedCholesky;
  std::size_t index(int i, int j) const {
    return static_cast<std::size_t>(i) * static_cast<std::size_t>(bandwidth_ + 1) +
           static_cast<std::size_t>(j - i + bandwidth_);
  }
  int size_ = 0;
  int bandwidth_ = 0;
  std::vector<double, DefaultInitAllocator<double>> lower_;
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
