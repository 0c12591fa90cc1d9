#include "argil/core/deform/pole_stencil_matrix.hpp"

#include <algorithm>
#include <cassert>

namespace argil {

PoleStencilMatrix::PoleStencilMatrix(int count_u, int count_v, int reach_u, int reach_v)
    : count_u_(count_u),
      count_v_(count_v),
      reach_u_(reach_u),
      reach_v_(reach_v),
      values_(static_cast<std::size_t>(count_u) * static_cast<std::size_t>(count_v) *
                  static_cast<std::size_t>((2 * reach_u + 1) * (2 * reach_v + 1)),
              0.0) {}

double PoleStencilMatrix::diagonal(Eigen::Index pole) const {
  const int i = static_cast<int>(pole / count_v_);
  const int j = static_cast<int>(pole % count_v_);
  return at(i, j, 0, 0);
}

Eigen::MatrixXd PoleStencilMatrix::multiply(const Eigen::Ref<const Eigen::MatrixXd>& x) const {
  assert(x.rows() == size());
  Eigen::MatrixXd y(x.rows(), x.cols());
  multiply_rows(x, 0, count_u_, 0, count_v_, y);
  return y;
}

void PoleStencilMatrix::row_sums(const double* const (&column)[3], int i, int j,
                                 double (&sum)[3]) const {
  // Along dj both a stencil row and a column of x are contiguous. Three
  // columns at a time, each its own sum (three independent chains of adds).
  const int di_lo = std::max(-reach_u_, -i), di_hi = std::min(reach_u_, count_u_ - 1 - i);
  const int dj_lo = std::max(-reach_v_, -j), dj_hi = std::min(reach_v_, count_v_ - 1 - j);
  const Eigen::Index a = static_cast<Eigen::Index>(i) * count_v_ + j;
  const double* stencil = values_.data() + static_cast<std::size_t>(a) * width_u() * width_v();
  sum[0] = sum[1] = sum[2] = 0.0;
  for (int di = di_lo; di <= di_hi; ++di) {
    const double* k = stencil + (di + reach_u_) * width_v() + reach_v_;
    const Eigen::Index b = static_cast<Eigen::Index>(i + di) * count_v_ + j;
    for (int dj = dj_lo; dj <= dj_hi; ++dj) {
      sum[0] += k[dj] * column[0][b + dj];
      sum[1] += k[dj] * column[1][b + dj];
      sum[2] += k[dj] * column[2][b + dj];
    }
  }
}

void PoleStencilMatrix::multiply_rows(const Eigen::Ref<const Eigen::MatrixXd>& x, int i0, int i1,
                                      int j0, int j1, Eigen::Ref<Eigen::MatrixXd> y) const {
  // Columns go three at a time (the order within a column is the same, so
  // so are the bits).
  const Eigen::Index cols = x.cols();
  for (int i = std::max(0, i0); i < std::min(i1, count_u_); ++i) {
    for (int j = std::max(0, j0); j < std::min(j1, count_v_); ++j) {
      const Eigen::Index a = static_cast<Eigen::Index>(i) * count_v_ + j;
      for (Eigen::Index c0 = 0; c0 < cols; c0 += 3) {
        const int n = static_cast<int>(std::min<Eigen::Index>(3, cols - c0));
        const double* const column[3] = {x.col(c0).data(), x.col(c0 + (n > 1 ? 1 : 0)).data(),
                                         x.col(c0 + (n > 2 ? 2 : 0)).data()};
        double sum[3];
        row_sums(column, i, j, sum);
        for (int c = 0; c < n; ++c) y(a, c0 + c) = sum[c];
      }
    }
  }
}

Eigen::RowVector3d PoleStencilMatrix::row_product(const Eigen::Ref<const Eigen::MatrixXd>& x, int i,
                                                  int j) const {
  assert(x.rows() == size() && x.cols() == 3);
  const double* const column[3] = {x.col(0).data(), x.col(1).data(), x.col(2).data()};
  double sum[3];
  row_sums(column, i, j, sum);
  return {sum[0], sum[1], sum[2]};
}

double PoleStencilMatrix::quadratic_form(const Eigen::Ref<const Eigen::MatrixXd>& x) const {
  return (x.array() * multiply(x).array()).sum();
}

void PoleStencilMatrix::add_scaled(const PoleStencilMatrix& other, double scale) {
  for (std::size_t k = 0; k < values_.size(); ++k) values_[k] += scale * other.values_[k];
}

}  // namespace argil
