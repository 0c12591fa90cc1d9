#pragma once
// Material of a deformable surface in physical units (docs/deformation.md),
// its documented range and named presets.
//
// Units (docs/conventions.md): lengths [mm], time [s], force [N], mass [kg];
// stresses and moduli in N/mm^2 = MPa. Newton's law in these units reads
// F [N] = 1e-3 m [kg] a [mm/s^2]: the solver multiplies masses by
// kMassToNewtonSecond2PerMm before using them.
//
// Every quantity is a property of the material (or of how it is held), never
// of the control net: refining a face exactly does not change how it feels.

#include <limits>
#include <optional>
#include <string_view>
#include <vector>

#include "argil/core/base/number_text.hpp"
#include "argil/core/base/status.hpp"

namespace argil {

/// 1 kg = 1e-3 N s^2 / mm: the mass unit that makes F = m a hold with a in mm/s^2.
inline constexpr double kMassToNewtonSecond2PerMm = 1e-3;
/// 1 kg/m^3 = 1e-9 kg/mm^3.
inline constexpr double kKgPerM3ToKgPerMm3 = 1e-9;

/// A thin layer of material over the face: a shell of `thickness` with
/// membrane and bending stiffness from Young's modulus and Poisson's ratio,
/// resting on an elastic foundation (the anchor) that pulls it home.
struct Material {
  /// Density [kg/m^3] (clay 1800, steel 7850). Mass per area = density x thickness.
  double density = 1800.0;
  /// Thickness of the sculpted layer [mm].
  double thickness = 5.0;
  /// Young's modulus E [MPa = N/mm^2].
  double youngs_modulus = 0.5;
  /// Poisson's ratio nu [-], in [0, 0.5).
  double poisson_ratio = 0.45;
  /// Foundation (anchor) stiffness per area [N/mm^3 = MPa/mm]: the pressure
  /// that pulls the surface back per mm of displacement. 0 = free.
  double foundation_stiffness = 0.1;
  /// Rayleigh stiffness-proportional damping beta [s]: every elastic term has a
  /// dashpot beta x its stiffness in parallel.
  double damping = 1e-3;
  /// Plastic yield [mm]: the largest displacement of a control point from its
  /// rest position that stays elastic; beyond it the rest position follows.
  /// +infinity = purely elastic.
  double yield = std::numeric_limits<double>::infinity();
  // Friction belongs to the tool-body pair (HapticWorld::add_deformable).
};

/// Stiffnesses a material gives a shell.
struct ShellStiffness {
  double membrane = 0.0;       // A = E h / (1 - nu^2) [N/mm]
  double bending = 0.0;        // D = E h^3 / (12 (1 - nu^2)) [N mm]
  double foundation = 0.0;     // k_a [N/mm^3]
  double mass_per_area = 0.0;  // rho h [kg/mm^2]
};
ShellStiffness shell_stiffness(const Material& material);

/// Documented range of each Material field, in the field's unit. validate()
/// and the scene reader both check against these, so they agree.
struct MaterialRange {
  Interval density{1e-3, 1e5};                                // [kg/m^3]; aerogel 1, osmium 22600
  Interval thickness{1e-6, 1e4};                              // [mm]
  Interval youngs_modulus{0.0, 1e7};                          // [MPa], 0 = no membrane or bending
  Interval poisson_ratio{0.0, 0.5, IntervalEnds::open_high};  // [-]
  Interval foundation_stiffness{0.0, 1e9};                    // [N/mm^3], 0 = free
  Interval damping{0.0, 1.0};                                 // [s]
  /// [mm]; the closed upper end is +infinity, purely elastic.
  Interval yield{1e-9, std::numeric_limits<double>::infinity()};
  /// Smallest ratio (m' + h^2 k_a a) / (h^2 k) of a control point at the
  /// haptic step h, m' its lumped mass, a its area and k its elastic diagonal
  /// stiffness. Below it the step could not resolve the body's rigid motion
  /// to about 1e-6 (rounding divided by the ratio), so DeformableBody caps the
  /// elastic stiffness to reach it: modes that stiff (omega h >= 1e5) are
  /// frozen at the haptic rate anyway. Low enough that refining a clay face
  /// to 0.6 mm spans beside C0 joins (surf114.igs) needs no cap, since a cap
  /// softens the material on the finer net. Dimensionless.
  double min_inertia_ratio = 1e-10;
};
inline constexpr MaterialRange kMaterialRange{};

/// ok, or invalid_argument naming the first field outside its range (in
/// declaration order), its value and the range in the field's unit. NaN is out of range.
Status validate(const Material& material);

/// A named material (clay, wax, foam, sheet_steel, aluminium, abs): typical
/// values, listed in docs/deformation.md.
struct MaterialPreset {
  std::string_view name;
  std::string_view description;
  Material material;
};
const std::vector<MaterialPreset>& material_presets();
/// The preset called `name`, or nullopt.
std::optional<Material> material_preset(std::string_view name);

/// Which boundaries of a deformable surface are held at their rest position.
/// Edges are u = u_min (fixed_u0), u = u_max (fixed_u1), v = v_min, v = v_max;
/// a held edge holds its row of control points (the boundary curve).
/// fixed_corners holds only the four corner control points. All false = free.
struct BoundaryConditions {
  bool fixed_u0 = false;
  bool fixed_u1 = false;
  bool fixed_v0 = false;
  bool fixed_v1 = false;
  bool fixed_corners = false;
};

}  // namespace argil
