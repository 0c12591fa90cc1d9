#pragma once
// The material of a version-1 scene (a mass-spring net: areal density, one
// spring stiffness, anchors per node) and its documented mapping to the
// physical argil::Material (docs/formats.md, "Version 1 scenes"). The mapping
// keeps the mass per area and the membrane stiffness; the dynamic NURBS model
// still feels different from the old springs.

#include <limits>

#include "argil/core/base/number_text.hpp"
#include "argil/core/base/status.hpp"
#include "argil/core/deform/material.hpp"

namespace argil::sculpt {

/// A version-1 scene's "material" (friction apart, which is not a material field).
struct Version1Material {
  double density = 2e-5;          // areal density [kg/mm^2]
  double stiffness = 1.0;         // every structural, shear and bending spring [N/mm]
  double damping = 1e-3;          // Rayleigh beta [s]
  double anchor_stiffness = 1.0;  // spring from each node to its rest position [N/mm]
  double yield = std::numeric_limits<double>::infinity();  // largest elastic stretch [mm]
};

/// The ranges version-1 scenes were checked against (the old validate()).
struct Version1MaterialRange {
  Interval density{1e-15, 1e3};                                   // [kg/mm^2]
  Interval stiffness{0.0, 1e9};                                   // [N/mm]
  Interval damping{0.0, 1.0};                                     // [s]
  Interval anchor_stiffness{0.0, 1e9};                            // [N/mm]
  Interval yield{1e-9, std::numeric_limits<double>::infinity()};  // [mm]
};
inline constexpr Version1MaterialRange kVersion1MaterialRange{};

/// The thickness a mapped material gets when the ranges of kMaterialRange allow it [mm].
inline constexpr double kVersion1Thickness = 1.0;
/// The surface area one version-1 anchor is taken to hold [mm^2].
inline constexpr double kVersion1AnchorArea = 1.0;

/// The physical material of a version-1 material:
///  - thickness h = kVersion1Thickness, moved to the nearest thickness that
///    keeps density and youngs_modulus inside kMaterialRange;
///  - density = areal density / h (mass per area kept);
///  - poisson_ratio 0 and youngs_modulus = stiffness / h, so the membrane
///    stiffness E h / (1 - nu^2) equals the old spring stiffness;
///  - foundation_stiffness = anchor_stiffness / kVersion1AnchorArea;
///  - damping and yield unchanged.
/// invalid_argument naming the field ("density", "stiffness", ...) when a
/// value is outside kVersion1MaterialRange or has no physical counterpart
/// inside kMaterialRange (an areal density above 1 kg/mm^2, say).
Result<Material> material_from_version1(const Version1Material& old);

}  // namespace argil::sculpt
