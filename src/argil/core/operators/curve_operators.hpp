#pragma once
// The paper's "transformation matrices" for one direction: everything that maps
// control points to samples, Bezier nets or back, depending only on the degree
// and the knot vector. Built once per structure, shared through OperatorCache,
// never recomputed when control points move.

#include <Eigen/Core>
#include <map>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

#include "argil/core/base/status.hpp"
#include "argil/core/geometry/bezier.hpp"
#include "argil/core/linalg/banded_lu.hpp"

namespace argil {

/// Basis rows at a list of parameters: sample k uses control points
/// first_pole[k] .. first_pole[k] + degree with weights values.row(k) (and
/// derivatives d1, d2 per unit parameter).
struct SamplingRows {
  Eigen::VectorXd params;
  std::vector<int> first_pole;
  Eigen::MatrixXd values;  // params.size() x (degree + 1)
  Eigen::MatrixXd d1;
  Eigen::MatrixXd d2;
  Eigen::Index size() const { return params.size(); }
};

/// Operators of one direction (degree + clamped knot vector).
class CurveOperators {
 public:
  /// Precondition: the knots pass validate() (clamped, multiplicities <= degree).
  /// Fails only when the collocation matrix cannot be factorised.
  static Result<std::shared_ptr<const CurveOperators>> build(int degree,
                                                             const Eigen::VectorXd& knots);

  int degree() const { return degree_; }
  const Eigen::VectorXd& knots() const { return knots_; }
  int count() const { return static_cast<int>(knots_.size()) - degree_ - 1; }

  /// Non-empty spans and their Bezier extraction operators.
  const BezierExtraction& extraction() const { return extraction_; }
  int element_count() const { return static_cast<int>(extraction_.spans.size()); }
  /// Split matrices of a degree-p Bezier segment at 1/2.
  const SubdivisionMatrices& subdivision() const { return subdivision_; }

  /// Rows at level L: every element sampled at 2^L equal steps, plus the end
  /// of the domain (element_count() * 2^L + 1 parameters). Built on first use
  /// and kept; safe to call from several threads.
  const SamplingRows& level_rows(int level) const;
  /// Rows at arbitrary parameters (clamped to the domain); the caller keeps them.
  SamplingRows sampling_rows(const Eigen::VectorXd& params) const;

  /// Greville abscissae: the node parameters, one per control point.
  const Eigen::VectorXd& greville() const { return greville_; }
  /// Basis rows at the Greville abscissae (the collocation matrix, row form).
  const SamplingRows& greville_rows() const { return greville_rows_; }
  /// Factorised collocation matrix A(i, j) = N_j(greville_i).
  const BandedLU& collocation() const { return collocation_; }
  /// 1-norm condition number of the collocation matrix.
  double collocation_condition() const { return collocation_.condition_1norm(); }

 private:
  CurveOperators() = default;

  int degree_ = 1;
  Eigen::VectorXd knots_;
  BezierExtraction extraction_;
  SubdivisionMatrices subdivision_;
  Eigen::VectorXd greville_;
  SamplingRows greville_rows_;
  BandedLU collocation_;
  mutable std::mutex levels_mutex_;
  mutable std::vector<std::unique_ptr<SamplingRows>> levels_;
};

/// Shares CurveOperators between all surfaces (and both directions) with the
/// same degree and bit-identical knots.
class OperatorCache {
 public:
  Result<std::shared_ptr<const CurveOperators>> get(int degree, const Eigen::VectorXd& knots);
  std::size_t size() const;

 private:
  using Key = std::pair<int, std::vector<double>>;
  mutable std::mutex mutex_;
  std::map<Key, std::shared_ptr<const CurveOperators>> entries_;
};

}  // namespace argil
