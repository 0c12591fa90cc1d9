#pragma once
// A symmetric matrix over the control points of a face, stored as one dense
// stencil per control point: entry (a, b) is non-zero only when the supports
// of the two basis functions overlap, |i_a - i_b| <= p and |j_a - j_b| <= q.
// Memory and products cost n (2p + 1)(2q + 1), independent of the ordering.

#include <Eigen/Core>
#include <vector>

#include "argil/core/geometry/bspline_surface.hpp"

namespace argil {

class PoleStencilMatrix {
 public:
  PoleStencilMatrix() = default;
  /// Zero matrix over a count_u x count_v net with basis reach (p, q).
  PoleStencilMatrix(int count_u, int count_v, int reach_u, int reach_v);

  int count_u() const { return count_u_; }
  int count_v() const { return count_v_; }
  int reach_u() const { return reach_u_; }
  int reach_v() const { return reach_v_; }
  Eigen::Index size() const { return static_cast<Eigen::Index>(count_u_) * count_v_; }

  /// Adds `value` to entry (a, b) of poles a = (i, j) and b = (i + di, j + dj),
  /// |di| <= reach_u, |dj| <= reach_v. Callers add both (a, b) and (b, a).
  void add(int i, int j, int di, int dj, double value) { entry(i, j, di, dj) += value; }
  /// Entry between pole (i, j) and pole (i + di, j + dj).
  double at(int i, int j, int di, int dj) const { return values_[index(i, j, di, dj)]; }
  double diagonal(Eigen::Index pole) const;

  /// K x for x with one row per pole (row i * count_v + j), any columns.
  Eigen::MatrixXd multiply(const Eigen::Ref<const Eigen::MatrixXd>& x) const;
  /// Rows (i, j), i0 <= i < i1, j0 <= j < j1, of K x into the same rows of y
  /// (overwritten; other rows untouched), each summed as multiply() sums it
  /// (over di, then dj).
  void multiply_rows(const Eigen::Ref<const Eigen::MatrixXd>& x, int i0, int i1, int j0, int j1,
                     Eigen::Ref<Eigen::MatrixXd> y) const;
  /// Row (i, j) of K x for x with three columns, summed as multiply_rows sums it.
  Eigen::RowVector3d row_product(const Eigen::Ref<const Eigen::MatrixXd>& x, int i, int j) const;
  /// sum over columns c of x_c^T K x_c.
  double quadratic_form(const Eigen::Ref<const Eigen::MatrixXd>& x) const;
  /// this += scale * other (same structure).
  void add_scaled(const PoleStencilMatrix& other, double scale);

 private:
  double& entry(int i, int j, int di, int dj) { return values_[index(i, j, di, dj)]; }
  /// Row (i, j) of K times three columns of one-row-per-pole data.
  void row_sums(const double* const (&column)[3], int i, int j, double (&sum)[3]) const;
  std::size_t index(int i, int j, int di, int dj) const {
    const std::size_t pole = static_cast<std::size_t>(i) * static_cast<std::size_t>(count_v_) +
                             static_cast<std::size_t>(j);
    return pole * static_cast<std::size_t>(width_u() * width_v()) +
           static_cast<std::size_t>((di + reach_u_) * width_v() + (dj + reach_v_));
  }
  int width_u() const { return 2 * reach_u_ + 1; }
  int width_v() const { return 2 * reach_v_ + 1; }

  int count_u_ = 0;
  int count_v_ = 0;
  int reach_u_ = 0;
  int reach_v_ = 0;
  std::vector<double> values_;
};

}  // namespace argil
