#include "argil/core/deform/pole_stencil_matrix.hpp"

#include <algorithm>

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
  Eigen::MatrixXd y = Eigen::MatrixXd::Zero(x.rows(), x.cols());
  for (int i = 0; i < count_u_; ++i) {
    for (int j = 0; j < count_v_; ++j) {
      const Eigen::Index a = static_cast<Eigen::Index>(i) * count_v_ + j;
      for (int di = std::max(-reach_u_, -i); di <= std::min(reach_u_, count_u_ - 1 - i); ++di) {
        for (int dj = std::max(-reach_v_, -j); dj <= std::min(reach_v_, count_v_ - 1 - j); ++dj) {
          const double k = at(i, j, di, dj);
          if (k == 0.0) continue;
          const Eigen::Index b = static_cast<Eigen::Index>(i + di) * count_v_ + (j + dj);
          y.row(a) += k * x.row(b);
        }
      }
    }
  }
  return y;
}

void PoleStencilMatrix::multiply_rows(const Eigen::Ref<const Eigen::MatrixXd>& x, int i0, int i1,
                                      int j0, int j1, Eigen::Ref<Eigen::MatrixXd> y) const {
  for (int i = std::max(0, i0); i < std::min(i1, count_u_); ++i) {
    for (int j = std::max(0, j0); j < std::min(j1, count_v_); ++j) {
      const Eigen::Index a = static_cast<Eigen::Index>(i) * count_v_ + j;
      y.row(a).setZero();
      for (int di = std::max(-reach_u_, -i); di <= std::min(reach_u_, count_u_ - 1 - i); ++di) {
        for (int dj = std::max(-reach_v_, -j); dj <= std::min(reach_v_, count_v_ - 1 - j); ++dj) {
          const double k = at(i, j, di, dj);
          if (k == 0.0) continue;
          const Eigen::Index b = static_cast<Eigen::Index>(i + di) * count_v_ + (j + dj);
          y.row(a) += k * x.row(b);
        }
      }
    }
  }
}

double PoleStencilMatrix::quadratic_form(const Eigen::Ref<const Eigen::MatrixXd>& x) const {
  return (x.array() * multiply(x).array()).sum();
}

void PoleStencilMatrix::add_scaled(const PoleStencilMatrix& other, double scale) {
  for (std::size_t k = 0; k < values_.size(); ++k) values_[k] += scale * other.values_[k];
}

}  // namespace argil
