#include "argil/core/linalg/psd_pseudo_inverse.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

namespace argil {
namespace {

/// Pivots at or below this fraction of the largest diagonal entry end the
/// range: rounding, not rank.
constexpr double kRangePivot = 1e-14;

/// Above this share of the size, the range costs more than it saves (the
/// eigensolver's cost grows with the cube of the size it is given).
constexpr double kRangeFirstShare = 0.6;

/// L (m x r) with L L^T = g up to pivots of at most kRangePivot of g's
/// largest diagonal entry, by Cholesky with diagonal pivoting; nothing when
/// r would pass `max_rank`.
std::optional<Eigen::MatrixXd> pivoted_range(const Eigen::MatrixXd& g, Eigen::Index max_rank) {
  const Eigen::Index m = g.rows();
  Eigen::VectorXd d = g.diagonal();  // the remaining Schur complement's diagonal
  const double cut = kRangePivot * std::max(d.maxCoeff(), 0.0);
  std::vector<char> used(static_cast<std::size_t>(m), 0);
  Eigen::MatrixXd l(m, max_rank);
  Eigen::Index r = 0;
  for (; r < m; ++r) {
    Eigen::Index p = -1;
    double best = cut;
    for (Eigen::Index i = 0; i < m; ++i) {
      if (!used[static_cast<std::size_t>(i)] && d[i] > best) {
        best = d[i];
        p = i;
      }
    }
    if (p < 0) break;
    if (r == max_rank) return std::nullopt;
    used[static_cast<std::size_t>(p)] = 1;
    const double root = std::sqrt(d[p]);
    l.col(r) = g.col(p);
    if (r > 0) l.col(r).noalias() -= l.leftCols(r) * l.row(p).head(r).transpose();
    l.col(r) /= root;
    for (Eigen::Index i = 0; i < m; ++i) {
      if (!used[static_cast<std::size_t>(i)]) {
        d[i] -= l(i, r) * l(i, r);
      } else {
        l(i, r) = i == p ? root : 0.0;  // rows already pivoted: exactly triangular
      }
    }
  }
  return Eigen::MatrixXd(l.leftCols(r));
}

/// The eigenvectors q of `s` whose eigenvalues mu pass floor times the
/// largest, as columns q / sqrt(mu); nothing if the solver fails.
std::optional<Eigen::MatrixXd> inverse_root_columns(const Eigen::MatrixXd& s, double floor) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(s);
  if (eigen.info() != Eigen::Success) return std::nullopt;
  const Eigen::VectorXd& mu = eigen.eigenvalues();
  const double least = floor * std::max(mu.cwiseAbs().maxCoeff(), 1e-300);
  std::vector<Eigen::Index> kept;
  for (Eigen::Index k = 0; k < mu.size(); ++k)
    if (mu[k] > least) kept.push_back(k);
  Eigen::MatrixXd columns(s.rows(), static_cast<Eigen::Index>(kept.size()));
  for (std::size_t k = 0; k < kept.size(); ++k) {
    const Eigen::Index c = kept[k];
    columns.col(static_cast<Eigen::Index>(k)) =
        eigen.eigenvectors().col(c) * (1.0 / std::sqrt(mu[c]));
  }
  return columns;
}

}  // namespace

Eigen::MatrixXd psd_pseudo_inverse_factor(const Eigen::MatrixXd& g, double floor,
                                          PseudoInverseMethod method) {
  const Eigen::Index m = g.rows();
  const Eigen::MatrixXd none(m, 0);
  // The range path reads only the columns it pivots on: a NaN elsewhere
  // would pass unseen (the whole decomposition fails on it).
  if (m == 0 || !g.allFinite()) return none;
  if (method != PseudoInverseMethod::eigen_of_whole) {
    const Eigen::Index max_rank =
        method == PseudoInverseMethod::range_first
            ? m
            : static_cast<Eigen::Index>(kRangeFirstShare * static_cast<double>(m));
    if (const std::optional<Eigen::MatrixXd> l = pivoted_range(g, max_rank)) {
      const Eigen::Index r = l->cols();
      if (r == 0) return none;
      // L = Q R (Q orthonormal): G's eigenpairs are (mu, Q v) for those of
      // R R^T. (From L^T L instead, q = L u / sqrt(mu) magnified the
      // rounding of u by up to sqrt(mu_max / mu): multipliers 4e-3 off the
      // whole decomposition's on a real joint; 5e-6 this way, where the
      // whole's own move by 8e-6 when G's entries move by a rounding unit.)
      const Eigen::HouseholderQR<Eigen::MatrixXd> qr(*l);
      const Eigen::MatrixXd upper = qr.matrixQR().topRows(r).triangularView<Eigen::Upper>();
      const std::optional<Eigen::MatrixXd> v =
          inverse_root_columns(upper * upper.transpose(), floor);
      if (!v) return none;
      Eigen::MatrixXd f = Eigen::MatrixXd::Zero(m, v->cols());
      f.topRows(r) = *v;
      f.applyOnTheLeft(qr.householderQ());
      return f;
    }
  }
  const std::optional<Eigen::MatrixXd> f = inverse_root_columns(g, floor);
  return f ? *f : none;
}

}  // namespace argil
