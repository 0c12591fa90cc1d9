#pragma once
// Two faces joined along the edge they share (docs/deformation.md, Joined
// faces). At points sampled along the edge the joint asks that both faces
// move alike (G0: d_a(uv_a) = d_b(uv_b)) and that they turn alike about the
// edge (n_a . D_ca d_a = n_b . D_cb d_b, c = n x e each face's direction
// across the edge e): the angle between them is kept, so a G1 edge stays G1
// and a crease keeps its angle.
// Both conditions are linear in the two nets: rows A over the poles the
// samples reach. The joint acts by edge forces f = A^T lambda on both nets.
// Each body's step is linear in its load, so a force changes its step by
// h^2 S^-1 f (DeformableBody::step_response, S the step's matrix); after the
// bodies stepped, the joint solves the small system (A h^2 S^-1 A^T) lambda =
// -A (P - P_0) and adds that motion: the result is the implicit step of the
// joined pair, and the neighbour deforms with the face near the edge. The
// forces are kept and applied in later steps, so a held edge does not spring
// open again.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <numbers>
#include <utility>
#include <vector>

#include "argil/core/base/status.hpp"
#include "argil/core/deform/deformable_body.hpp"
#include "argil/core/geometry/bspline_curve.hpp"
#include "argil/core/geometry/bspline_surface.hpp"

namespace argil {

/// Faces whose normals along an edge agree within this angle [rad] meet
/// tangent-continuously (G1) there (the joint keeps every angle; this one
/// counts the G1 samples).
inline constexpr double kTangentJoinAngle = std::numbers::pi / 180.0;

/// One point of a shared edge, in each face's (u, v).
struct EdgeSample {
  Eigen::Vector2d uv_a = Eigen::Vector2d::Zero();
  Eigen::Vector2d uv_b = Eigen::Vector2d::Zero();
};

/// Points along an edge that faces a and b share, given by its curve in each
/// face's (u, v) (both from the edge's start to its end, at any pace): evenly
/// spaced in a's curve parameter, at least three per knot span either face
/// has along the edge (16 to 96), each matched on b by the point of b's curve
/// nearest in space.
std::vector<EdgeSample> sample_shared_edge(const BSplineSurface& a, const BSplineCurve& pcurve_a,
                                           const BSplineSurface& b, const BSplineCurve& pcurve_b);

/// One face of a joint: its surface at rest and which poles are held
/// (empty: none). A rigid face holds every pole.
struct JointFace {
  const BSplineSurface* surface = nullptr;
  std::vector<char> held;
};

/// What a joint's correction does to one face: its poles move and gain
/// velocity, and the joint's forces on it grow.
struct PoleCorrection {
  std::vector<Eigen::Index> poles;
  ControlNet points;                 // added to the control points [mm]
  ControlNet velocities;             // added to their velocities [mm/s]
  std::vector<Eigen::Index> loaded;  // poles the joint pushes
  ControlNet forces;                 // added to the joint's forces on them [N]
};

class EdgeJoint {
 public:
  /// `seam`: a and b are one face (a closed surface's two boundaries), whose
  /// poles are one set. Fails when the samples are fewer than two or the held
  /// flags do not match the nets.
  static Result<EdgeJoint> create(const JointFace& a, const JointFace& b,
                                  const std::vector<EdgeSample>& samples, bool seam);

  bool seam() const { return seam_; }
  /// Samples where the faces meet tangent-continuously (G1).
  int tangent_count() const { return tangent_count_; }

  /// The poles of face `side` (0: a, 1: b; a seam has only side 0) the
  /// joint's forces act on, and those forces per unit multiplier as scalar
  /// fields (K acts alike on x, y and z, so a scalar response serves all
  /// three): for S samples, column k is sample k's G0 force (in each
  /// coordinate), columns S + k and 2 S + k its turn force along face a's and
  /// face b's normal.
  std::vector<Eigen::Index> loaded_poles(int side) const;
  RowMajorMatrix unit_forces(int side) const;
  /// Gives the joint each deformable face's response to unit_forces over a
  /// step of `dt` [s] (DeformableBody::step_response; an empty response for a
  /// rigid face). Must precede correction().
  void set_response(const StepResponse& a, const StepResponse& b, double dt);
  bool ready() const { return response_dt_ > 0.0; }
  double response_dt() const { return response_dt_; }

  /// The corrections of a's and b's poles (b's empty for a seam) that restore
  /// the joint for nets `pa`, `pb`; their largest residual before correction
  /// is `residual` [mm]. With a residual of at most `slack` [mm] nothing is
  /// corrected (a body at rest is not woken by rounding).
  struct Correction {
    PoleCorrection a, b;
    double residual = 0.0;
  };
  Correction correction(const ControlNet& pa, const ControlNet& pb, double slack) const;

 private:
  EdgeJoint() = default;
  /// The unknowns' positions, three per unknown.
  Eigen::VectorXd gather(const ControlNet& pa, const ControlNet& pb) const;
  /// G^+ b: the multipliers for residual b.
  Eigen::VectorXd pseudo_solve(const Eigen::VectorXd& b) const;
  /// How a face's response poles move for multipliers `lambda` (one per row of A).
  Eigen::MatrixXd motion_of(const StepResponse& r, const Eigen::VectorXd& lambda) const;

  /// The scalar coefficients behind sample k's rows of A: its G0 rows
  /// (the same in x, y and z) and its turn row (per face, times its normal).
  struct SampleRows {
    std::vector<std::pair<int, double>> value;  // (unknown, coefficient)
    std::array<std::vector<std::pair<int, double>>, 2> turn;
    std::array<Eigen::Vector3d, 2> normal;
    Eigen::Index g0_row = 0;     // its x row (then y, z)
    Eigen::Index turn_row = -1;  // -1: no turn row (a degenerate edge direction)
  };
  std::vector<SampleRows> scalar_;

  bool seam_ = false;
  std::vector<char> tangent_;  // per sample
  int tangent_count_ = 0;
  std::vector<int> side_;           // of each unknown: 0 (a) or 1 (b)
  std::vector<Eigen::Index> pole_;  // of each unknown
  Eigen::VectorXd rest_;            // the unknowns at rest, three per unknown
  /// A: one row per condition, three columns per unknown.
  Eigen::SparseMatrix<double, Eigen::RowMajor> rows_;
  std::array<StepResponse, 2> response_;
  // G^+ = F F^T (psd_pseudo_inverse.hpp), over G = A h^2 S^-1 A^T's
  // eigenpairs above the floor: G is singular (more samples than the nets
  // can follow), and a pivoted LDL^T with small pivots dropped is not a
  // pseudo-inverse there: on the screw's shank and cone it left a 0.4 mm gap
  // uncorrected.
  Eigen::MatrixXd inverse_factor_;  // one column q / sqrt(mu) per kept eigenpair
  double response_dt_ = 0.0;
};

}  // namespace argil
