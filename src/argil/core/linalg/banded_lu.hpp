#pragma once
// LU factorisation of a banded matrix without pivoting, for B-spline
// collocation matrices (totally positive, so elimination without pivoting is
// stable: de Boor, "A Practical Guide to Splines", BANFAC/BANSLV).

#include <Eigen/Core>

#include "argil/core/base/status.hpp"

namespace argil {

/// A square band matrix in LAPACK band storage: A(i, j) = band(upper + i - j, j)
/// inside the band j - upper <= i <= j + lower, zero outside.
struct BandedMatrix {
  int size = 0;
  int lower = 0;         // sub-diagonals
  int upper = 0;         // super-diagonals
  Eigen::MatrixXd band;  // (lower + upper + 1) x size

  BandedMatrix() = default;
  BandedMatrix(int n, int kl, int ku)
      : size(n), lower(kl), upper(ku), band(Eigen::MatrixXd::Zero(kl + ku + 1, n)) {}
  bool in_band(int i, int j) const { return j - upper <= i && i <= j + lower; }
  double& at(int i, int j) { return band(upper + i - j, j); }
  double at(int i, int j) const { return in_band(i, j) ? band(upper + i - j, j) : 0.0; }
  /// 1-norm: the largest column sum of absolute values.
  double norm1() const { return band.cwiseAbs().colwise().sum().maxCoeff(); }
};

/// The factors L (unit lower, `lower` bands) and U (`upper` bands) of A = L U,
/// stored in one band matrix. Solves in O(n (lower + upper)) per right-hand side.
class BandedLU {
 public:
  /// Factorises `a`; fails with numerical_failure on a zero or tiny pivot
  /// (relative to the matrix norm), which a valid collocation matrix never has.
  static Result<BandedLU> factorize(BandedMatrix a);

  int size() const { return lu_.size; }
  /// Solves A X = B in place; B has size() rows and any number of columns.
  void solve_in_place(Eigen::Ref<Eigen::MatrixXd> b) const;
  /// Solves A^T X = B in place (U^T then L^T): the adjoint of solve_in_place,
  /// which carries generalised forces back through a linear map.
  void solve_transpose_in_place(Eigen::Ref<Eigen::MatrixXd> b) const;
  /// Exact 1-norm condition number ||A||_1 ||A^-1||_1 (n solves, O(n^2 bandwidth)).
  double condition_1norm() const { return condition_; }

 private:
  BandedMatrix lu_;
  double condition_ = 0.0;
};

}  // namespace argil
