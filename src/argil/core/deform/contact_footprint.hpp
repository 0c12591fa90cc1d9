#pragma once
// The disc a sphere presses on (docs/deformation.md, "Loads"): a tool does not
// push at a point but over its contact patch, and a point load on a membrane
// has no limit as the net is refined (its dent grows with the log of the
// resolution). Spreading each contact's share over the sphere's contact disc
// gives a load the net resolves, the same on a face and on its refinements.

#include <Eigen/Core>
#include <vector>

#include "argil/core/collision/contact.hpp"
#include "argil/core/deform/contact_response.hpp"
#include "argil/core/geometry/bspline_surface.hpp"
#include "argil/core/geometry/trim_region.hpp"

namespace argil {

/// Radius [mm] of the disc a sphere of `sphere_radius` [mm] pressing with
/// `force` [N] rests on, on a face on a foundation of `foundation` [N/mm^3]:
/// the conforming (Winkler) contact, where the pressure k (delta - rho^2 / 2r)
/// over a disc of radius a carries F = pi k a^4 / (4 r), so
/// a = (4 r F / (pi k))^(1/4). At most the sphere's radius (a face without a
/// foundation, or a force that would sink the sphere past its equator); zero
/// for no force.
double sphere_contact_radius(double sphere_radius, double force, double foundation);

/// Control-point weights (as contact_load_pattern) of a unit force spread
/// over a disc of `radius` [mm] around each contact with the conforming
/// contact's paraboloid pressure, 1 - rho^2 / a^2: each contact's share is
/// carried by 36 points of the disc in its tangent plane, mapped to (u, v)
/// through the first-order map at the contact (S_u, S_v). Points outside the
/// face's domain or its trims carry nothing (there is no material there);
/// the others carry their pressure, rescaled so each contact keeps its share.
/// Non-negative and summing to 1; the moment is that of the mapped disc
/// points. `radius` 0 gives contact_load_pattern.
Eigen::VectorXd footprint_load_pattern(const BSplineSurface& surface,
                                       const std::vector<Contact>& contacts,
                                       const std::vector<double>& shares, double radius,
                                       const TrimRegion& trim);

/// footprint_load_pattern's non-zero entries (PoleWeights), computed without
/// touching the rest of the net.
PoleWeights footprint_pole_weights(const BSplineSurface& surface,
                                   const std::vector<Contact>& contacts,
                                   const std::vector<double>& shares, double radius,
                                   const TrimRegion& trim);

}  // namespace argil
