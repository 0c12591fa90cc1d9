#pragma once
// The shell energy of a face's displacement, integrated once over its rest
// surface (docs/deformation.md). The control net is the state: the
// displacement field is d(u, v) = sum_i R_i(u, v) dp_i (R the rational basis),
// so every energy below is a quadratic form in the control-point
// displacements dp, the same for x, y and z, with a matrix that depends only
// on the face's structure and rest shape.
//
// With a material's shell stiffnesses (membrane A, bending D, foundation k_a,
// shell_stiffness()), the elastic energy is
//   E(dp) = 1/2 sum_c dp_c^T (A Membrane + D (Bending + Joints) + k_a Foundation) dp_c
// and the lumped mass of control point i is rho h Area_i.

#include <Eigen/Core>

#include "argil/core/deform/pole_stencil_matrix.hpp"
#include "argil/core/geometry/bspline_surface.hpp"

namespace argil {

/// How much stiffer a C0 knot line of a face resists a change of its angle
/// than the bending of the material either side of it [-] (degree >= 2 across
/// the line; across a degree-1 direction the joints are the face's bending and
/// take factor 1).
inline constexpr double kJointStiffness = 100.0;

struct ShellMatrices {
  /// integral R_i dA [mm^2] (row sums of the consistent mass: positive, since R_i >= 0).
  Eigen::VectorXd area;
  double total_area = 0.0;  // [mm^2]
  /// integral R_i R_j dA [mm^2]: the foundation pulls every point home.
  PoleStencilMatrix foundation;
  /// integral g^ab R_i,a R_j,b dA [-]: the surface gradient of d (membrane).
  PoleStencilMatrix membrane;
  /// integral g^ac g^bd H_i,ab H_j,cd dA [1/mm^2], H_i the covariant Hessian
  /// R_i,ab - Gamma^c_ab R_i,c: the surface's bending (thin-plate energy).
  PoleStencilMatrix bending;
  /// Along every interior knot line of multiplicity >= degree (a C0 join,
  /// where the bending integral above cannot see a kink):
  /// integral kJointStiffness / h |d_n+ / |S_n+| - d_n- / |S_n-||^2 ds [1/mm^2],
  /// the jump of the cross-line derivative of d scaled to unit speed, h the
  /// mean width of the elements either side. Keeps the angle of the join: a
  /// G1 join stays G1, a crease stays a crease.
  PoleStencilMatrix joints;
};

/// Integrates the matrices over `rest` by Gauss-Legendre quadrature with
/// degree + 1 points per knot span and direction (2 degree + 2, at most 32, on
/// a rational face). Points where the surface is
/// degenerate (S_u x S_v vanishes, e.g. at a collapsed edge) carry no area and
/// are skipped. Precondition: validate(rest).ok().
ShellMatrices shell_matrices(const BSplineSurface& rest);

}  // namespace argil
