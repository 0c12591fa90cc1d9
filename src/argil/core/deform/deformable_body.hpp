#pragma once
// A deformable surface (docs/deformation.md): nodes at the Greville abscissae,
// springs and anchors (mass_spring.hpp), an implicit Euler step at the haptic
// rate, plasticity, and the exact fit back to control points every step.

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <vector>

#include "argil/core/deform/mass_spring.hpp"
#include "argil/core/deform/material.hpp"
#include "argil/core/geometry/bspline_surface.hpp"
#include "argil/core/hierarchy/surface_hierarchy.hpp"
#include "argil/core/linalg/banded_cholesky.hpp"

namespace argil {

/// Largest time step a body accepts [s] (the haptic step is 1e-3).
inline constexpr double kMaxTimeStep = 0.1;

/// What a step would do before a load whose size depends on it is known: the
/// motion of the loaded point without that load, and its compliance.
struct LoadPreview {
  /// g . (x_next - x) over the step without the pattern load [mm], g the pattern.
  Eigen::Vector3d free_motion = Eigen::Vector3d::Zero();
  /// h^2 g^T A^-1 g [mm/N]: how far the loaded point moves this step per newton
  /// applied through the pattern (the same in every direction).
  double compliance = 0.0;
};

/// State x (nodes), v (node velocities), x_rest (rest nodes) and a material.
/// One step, with h = dt and K, C = beta K, M' = 1e-3 M (mass_spring.hpp):
///   (M' + h C + h^2 K) v+ = M' v + h (f - K (x - x_rest)),  x+ = x + h v+
/// (implicit Euler, unconditionally stable for M' > 0, K, C >= 0; without
/// external force the energy 0.5 v^T M' v + 0.5 u^T K u never increases).
/// Fixed nodes keep x = x_rest and v = 0. After the step, plasticity moves
/// x_rest so no anchor stretch exceeds the yield, and the control points are
/// refitted exactly through the nodes (fit_control_points) and handed to the
/// hierarchy, so the next query sees the new surface.
class DeformableBody {
 public:
  /// Validates the surface and the material, builds the node layer and checks
  /// node masses against kMaterialRange (error names `density`).
  static Result<DeformableBody> create(const BSplineSurface& surface, const Material& material,
                                       const BoundaryConditions& conditions, OperatorCache& cache);

  /// Current surface (control points fitted to the nodes; weights unchanged).
  const BSplineSurface& surface() const { return hierarchy_.surface(); }
  const SurfaceHierarchy& hierarchy() const { return hierarchy_; }
  /// Largest node count of the lazy hierarchy (SurfaceHierarchy::set_node_budget).
  void set_node_budget(std::size_t nodes) { hierarchy_.set_node_budget(nodes); }
  const SurfaceOperators& operators() const { return hierarchy_.operators(); }
  const Material& material() const { return material_; }
  /// Node positions [mm], row i * n_v + j at (greville_u[i], greville_v[j]).
  const ControlNet& nodes() const { return nodes_; }
  /// Rest positions [mm]; they move only by plastic flow.
  const ControlNet& rest_nodes() const { return rest_; }
  const ControlNet& velocities() const { return velocities_; }  // [mm/s]
  const Eigen::VectorXd& masses() const { return masses_; }     // [kg]
  const std::vector<char>& fixed() const { return fixed_; }
  const std::vector<Spring>& springs() const { return springs_; }
  /// 0.5 sum m' |v|^2 [mJ = N mm].
  double kinetic_energy() const;
  /// Springs and anchors, 0.5 u^T K u with u = x - x_rest [mJ].
  double potential_energy() const;

  /// One step of dt [s] (0 < dt <= kMaxTimeStep) with explicit node forces
  /// (n x 3 [N]; empty for none). Fails only on an invalid dt or a matrix that
  /// is not positive definite to working precision (outside the documented range).
  Status step(double dt, const ControlNet& node_forces = {});

  /// The first half of a step with a load F spread by `pattern` (generalised
  /// node weights, n entries, e.g. fit_adjoint of a contact's basis values;
  /// empty for none) whose size is decided after seeing the preview. Must be
  /// followed by finish_step.
  Result<LoadPreview> begin_step(double dt, const ControlNet& node_forces,
                                 const Eigen::VectorXd& pattern);
  /// Completes the step with pattern force F [N] (node force g_i F).
  void finish_step(const Eigen::Vector3d& pattern_force);

 private:
  DeformableBody(SurfaceHierarchy hierarchy, const Material& material);
  Status factorize(double dt);

  SurfaceHierarchy hierarchy_;
  Material material_;
  std::vector<Spring> springs_;
  std::vector<char> fixed_;
  Eigen::VectorXd masses_;
  ControlNet rest_, nodes_, velocities_;
  std::optional<BandedCholesky> solver_;
  double solver_dt_ = 0.0;
  // Between begin_step and finish_step.
  RowMajorMatrix work_;
  double step_dt_ = 0.0;
  bool has_pattern_ = false;
};

}  // namespace argil
