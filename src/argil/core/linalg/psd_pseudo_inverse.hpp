#pragma once
// The Moore-Penrose pseudo-inverse of a symmetric positive semi-definite
// matrix, for the joints' multipliers (edge_joint.hpp): their matrix G has
// far more rows than rank on most real edges (72 of 360, 100 of 384), and a
// full eigendecomposition of G cost 20 to 40 ms there. A pivoted Cholesky
// finds G's range first (L L^T = G up to rounding-level pivots), and the
// eigenpairs come from the small matrix R R^T (L = Q R), whose eigenvalues
// are G's.

#include <Eigen/Core>

namespace argil {

/// How G^+ is built (for the tests and the bench).
enum class PseudoInverseMethod {
  automatic,      // range first while the pivoted Cholesky's rank is at most 3/5 of the size
  range_first,    // always the pivoted Cholesky, then eigenpairs of R R^T
  eigen_of_whole  // eigenpairs of G itself
};

/// F with G^+ = F F^T for the symmetric positive semi-definite `g`, where
/// the pseudo-inverse drops the eigenvalues at or below `floor` times the
/// largest: a column q / sqrt(mu) per kept eigenpair (mu, q), so a solve is
/// F (F^T b). No columns when every eigenvalue is below the floor, an entry
/// is not finite or the eigensolver fails. The result is unspecified for
/// a g that is not positive semi-definite.
/// The range is cut at pivots of 1e-14 of g's largest diagonal entry: what
/// it drops moves no eigenvalue by more than 1e-14 m of the largest, 4% of
/// a floor of 1e-10 for m = 384.
Eigen::MatrixXd psd_pseudo_inverse_factor(
    const Eigen::MatrixXd& g, double floor,
    PseudoInverseMethod method = PseudoInverseMethod::automatic);

}  // namespace argil
