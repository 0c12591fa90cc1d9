#pragma once
// The node layer (docs/deformation.md): one node per control point at the
// Greville abscissae, linear springs between them, anchors to the rest state.
//
// Springs are linear in the displacement u = x - x_rest: a spring between
// nodes a and b pulls with k ((u_b - u_a)), an anchor with -k_a u_a. So the
// stiffness matrix K = k Lap + k_a I (Lap the graph Laplacian of the spring
// stencil, the same for x, y and z) is constant, the system stays linear, and
// an implicit step factorises once. This is the small-displacement
// (zero-rest-length-difference) form; it does not resist rotations about the
// rest state differently from other motions, which the anchors dominate.

#include <Eigen/Core>
#include <vector>

#include "argil/core/deform/material.hpp"
#include "argil/core/geometry/bspline_surface.hpp"
#include "argil/core/linalg/banded_cholesky.hpp"
#include "argil/core/operators/surface_operators.hpp"

namespace argil {

enum class SpringKind { structural, shear, bending };

/// A spring between nodes a < b (rows i * n_v + j of the node grid).
struct Spring {
  int a = 0;
  int b = 0;
  SpringKind kind = SpringKind::structural;
};

/// Springs of an n_u x n_v node grid, in a fixed order (by a, then b):
/// structural (i,j)-(i+1,j) and (i,j)-(i,j+1); shear (i,j)-(i+1,j+1) and
/// (i+1,j)-(i,j+1); bending (i,j)-(i+2,j) and (i,j)-(i,j+2).
std::vector<Spring> grid_springs(int count_u, int count_v);

/// Largest |a - b| over the springs of an n_u x n_v grid: the half bandwidth
/// of the stiffness matrix (2 n_v once n_v >= 1 and n_u >= 3).
int grid_bandwidth(int count_u, int count_v);

/// Lumped node masses [kg]: `density` [kg/mm^2] times the area of the node's
/// Greville cell, |S_u x S_v| at the node times half the parameter distance to
/// its neighbours in each direction. A degenerate node (zero area, at a pole)
/// gets 1e-3 of the mean area so every mass is positive.
Eigen::VectorXd node_masses(const BSplineSurface& surface, const SurfaceOperators& ops,
                            double density);

/// Which nodes the boundary conditions hold (one flag per node).
std::vector<char> fixed_nodes(int count_u, int count_v, const BoundaryConditions& conditions);

/// The two constants of K = k Lap + k_a I [N/mm].
struct SpringConstants {
  double stiffness = 1.0;         // k, of every spring between nodes
  double anchor_stiffness = 1.0;  // k_a, of every node's anchor to its rest position
};

/// Internal plus anchor force on every node [N] for displacements u (n x 3 [mm]):
/// f = -(k Lap + k_a I) u. Fixed nodes get 0.
ControlNet elastic_forces(const std::vector<Spring>& springs, const SpringConstants& constants,
                          const ControlNet& displacement, const std::vector<char>& fixed);

/// Elastic energy 0.5 u^T K u [N mm = mJ].
double elastic_energy(const std::vector<Spring>& springs, const SpringConstants& constants,
                      const ControlNet& displacement);

/// What implicit_step_matrix() assembles besides the springs, masses and fixed nodes.
struct ImplicitStepRequest {
  int count_u = 0;  // node grid n_u x n_v (springs index rows i * n_v + j)
  int count_v = 0;
  Material material;  // stiffness, anchor stiffness and damping beta
  double dt = 0.0;    // time step h [s]
};

/// The implicit-Euler matrix M' + (h beta + h^2) K, M' = kMassToNewtonSecond2PerMm M,
/// in band form (lower half), for node masses [kg] and one fixed flag per node.
/// Rows and columns of fixed nodes are the identity.
SymmetricBandMatrix implicit_step_matrix(const std::vector<Spring>& springs,
                                         const Eigen::VectorXd& masses,
                                         const std::vector<char>& fixed,
                                         const ImplicitStepRequest& request);

}  // namespace argil
