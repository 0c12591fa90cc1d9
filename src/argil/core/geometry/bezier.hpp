#pragma once
// Bezier forms: per-span extraction operators of a B-spline basis, subdivision
// matrices of a Bezier segment, and Bezier patches (the hierarchy's nodes).

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "argil/core/geometry/evaluate.hpp"

namespace argil {

/// Extraction operators of one knot vector (Borden et al. 2011, built here by
/// local knot insertion): for each non-empty span `spans[e]`, the Bezier
/// control points of that span are `operators[e] * P.middleRows(spans[e] - degree, degree + 1)`.
struct BezierExtraction {
  std::vector<int> spans;                  // knot span index of each element
  std::vector<Eigen::MatrixXd> operators;  // (degree+1) x (degree+1) each
};
BezierExtraction bezier_extraction(int degree, const Eigen::VectorXd& knots);

/// de Casteljau split of a degree-p Bezier segment at t = 1/2: the halves'
/// control points are `left * B` and `right * B`.
struct SubdivisionMatrices {
  Eigen::MatrixXd left;   // (p+1) x (p+1), lower triangular
  Eigen::MatrixXd right;  // (p+1) x (p+1), upper triangular
};
SubdivisionMatrices subdivision_matrices(int degree);

/// Homogeneous control points of a patch, one per row; rows are contiguous,
/// so mapping a net touches memory in order.
using PatchNet = Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::RowMajor>;

/// A tensor-product Bezier patch in homogeneous coordinates (w x, w y, w z, w),
/// row a * (degree_v + 1) + b, over its own domain [0, 1]^2.
struct BezierPatch {
  int degree_u = 1;
  int degree_v = 1;
  PatchNet points;
};

/// Point of the patch at local (s, t) in [0, 1]^2.
Eigen::Vector3d evaluate(const BezierPatch& patch, double s, double t);

/// Point and derivatives with respect to the local (s, t) up to `order` (0, 1
/// or 2), rational by the quotient rule: no knot search, so the leaves of the
/// hierarchy evaluate through their own patch. Degree at most kMaxDegree.
SurfaceDerivatives evaluate_derivatives(const BezierPatch& patch, double s, double t, int order);

/// The patch with its net mapped by `m` along direction d: M * B for u,
/// B * M^T for v (rows of M give the new control points of each line of the
/// net in d). A sum of 4-vectors without temporaries: node refreshes run it
/// every tick. Preconditions: m is (degree_d + 1) x (degree_d + 1).
BezierPatch map_along(const BezierPatch& patch, Direction d, const Eigen::MatrixXd& m);

/// Which child of a patch subdivide() returns: in each direction either the
/// lower half (0), the upper half (1), or no split (nullopt).
struct PatchHalves {
  std::optional<int> u;
  std::optional<int> v;
};

/// Child patch over the halves `which` of the parent's [0, 1]^2, split with
/// the de Casteljau matrices `su` (degree_u) and `sv` (degree_v).
BezierPatch subdivide(const BezierPatch& patch, const SubdivisionMatrices& su,
                      const SubdivisionMatrices& sv, const PatchHalves& which);
/// The same into `child`, reusing its storage (a node refreshed every tick
/// allocates nothing). `child` must not be `patch`.
void subdivide_into(const BezierPatch& patch, const SubdivisionMatrices& su,
                    const SubdivisionMatrices& sv, const PatchHalves& which, BezierPatch& child);

}  // namespace argil
