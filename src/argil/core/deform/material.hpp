#pragma once
// Material of a deformable surface (docs/deformation.md) and its documented range.
//
// Units (docs/conventions.md): lengths [mm], time [s], force [N], mass [kg].
// Newton's law in these units reads F [N] = 1e-3 m [kg] a [mm/s^2]: the solver
// multiplies masses by kMassToNewtonSecond2PerMm before using them.

#include <limits>

#include "argil/core/base/number_text.hpp"
#include "argil/core/base/status.hpp"

namespace argil {

/// 1 kg = 1e-3 N s^2 / mm: the mass unit that makes F = m a hold with a in mm/s^2.
inline constexpr double kMassToNewtonSecond2PerMm = 1e-3;

/// A mass-spring material. Every field has a closed documented range that
/// validate() enforces; the bounds are kMaterialRange below.
struct Material {
  /// Areal density [kg/mm^2]: a node's mass is density times the surface area
  /// of its Greville cell (1 mm steel sheet: 7.85e-6; 10 mm clay slab: 2e-5).
  double density = 2e-5;
  /// Stiffness of every structural, shear and bending spring [N/mm]; 0 = none.
  double stiffness = 1.0;
  /// Rayleigh stiffness-proportional damping beta [s]: every spring and anchor
  /// has a dashpot beta * k in parallel. 0 = no physical damping (the implicit
  /// step still dissipates a little).
  double damping = 1e-3;
  /// Stiffness of the spring that pulls each node to its rest position [N/mm]; 0 = none.
  double anchor_stiffness = 1.0;
  /// Plastic yield: the largest anchor stretch |x - x_rest| [mm] that stays
  /// elastic. Beyond it the rest position follows the node so the stretch is
  /// exactly `yield`. +infinity = purely elastic.
  double yield = std::numeric_limits<double>::infinity();
  // Friction is not a material property here: it belongs to the tool-body
  // pair (HapticWorld::add_deformable, contact_response.hpp).
};

/// Documented range of each Material field, in the field's unit. validate()
/// and the scene reader both check against these, so they agree.
struct MaterialRange {
  Interval density{1e-15, 1e3};         // [kg/mm^2]
  Interval stiffness{0.0, 1e9};         // [N/mm], 0 = no springs
  Interval damping{0.0, 1.0};           // [s]
  Interval anchor_stiffness{0.0, 1e9};  // [N/mm], 0 = no anchors
  /// [mm]; the closed upper end is +infinity, purely elastic.
  Interval yield{1e-9, std::numeric_limits<double>::infinity()};
  /// Node masses a body accepts [kg] (density times node area): outside it the
  /// implicit system's conditioning (mass against dt^2 stiffness) is not
  /// guaranteed; DeformableBody::create reports it.
  Interval node_mass{1e-6, 1e3};
};
inline constexpr MaterialRange kMaterialRange{};

/// ok, or invalid_argument naming the first field outside its range (in
/// declaration order), its value and the range in the field's unit. NaN is out of range.
Status validate(const Material& material);

/// Which boundaries of a deformable surface are held at their rest position.
/// Edges are u = u_min (fixed_u0), u = u_max (fixed_u1), v = v_min, v = v_max;
/// fixed_corners holds only the four corner nodes. All false = free.
struct BoundaryConditions {
  bool fixed_u0 = false;
  bool fixed_u1 = false;
  bool fixed_v0 = false;
  bool fixed_v1 = false;
  bool fixed_corners = false;
};

}  // namespace argil
