#pragma once
// argil::core, the entry header. Modules from the bottom up (each includes only
// those above it in this list): base (status, results, number text), linalg (banded solvers, the
// pseudo-inverse), geometry (B-spline surfaces, evaluation, Bezier patches, tool shapes), operators
// (precomputed fitting and evaluation matrices), hierarchy (the conservative lazy bound tree),
// collision (queries and contacts), deform (materials and the deformable body), haptic (proxies,
// coupling, the tick).

// base
#include "argil/core/base/chunked_vector.hpp"  // IWYU pragma: export
#include "argil/core/base/number_text.hpp"     // IWYU pragma: export
#include "argil/core/base/resident_heap.hpp"   // IWYU pragma: export
#include "argil/core/base/status.hpp"          // IWYU pragma: export
// linalg
#include "argil/core/linalg/banded_cholesky.hpp"     // IWYU pragma: export
#include "argil/core/linalg/banded_lu.hpp"           // IWYU pragma: export
#include "argil/core/linalg/psd_pseudo_inverse.hpp"  // IWYU pragma: export
// geometry
#include "argil/core/geometry/basis.hpp"              // IWYU pragma: export
#include "argil/core/geometry/bezier.hpp"             // IWYU pragma: export
#include "argil/core/geometry/bspline_curve.hpp"      // IWYU pragma: export
#include "argil/core/geometry/bspline_surface.hpp"    // IWYU pragma: export
#include "argil/core/geometry/degree_elevation.hpp"   // IWYU pragma: export
#include "argil/core/geometry/evaluate.hpp"           // IWYU pragma: export
#include "argil/core/geometry/implicit_tool.hpp"      // IWYU pragma: export
#include "argil/core/geometry/knot_insertion.hpp"     // IWYU pragma: export
#include "argil/core/geometry/knot_vector.hpp"        // IWYU pragma: export
#include "argil/core/geometry/local_refinement.hpp"   // IWYU pragma: export
#include "argil/core/geometry/param_rect.hpp"         // IWYU pragma: export
#include "argil/core/geometry/pose.hpp"               // IWYU pragma: export
#include "argil/core/geometry/triangle_distance.hpp"  // IWYU pragma: export
#include "argil/core/geometry/trim_region.hpp"        // IWYU pragma: export
// operators
#include "argil/core/operators/curve_operators.hpp"    // IWYU pragma: export
#include "argil/core/operators/patch_evaluator.hpp"    // IWYU pragma: export
#include "argil/core/operators/surface_operators.hpp"  // IWYU pragma: export
// hierarchy
#include "argil/core/hierarchy/edge_crossings_bound.hpp"  // IWYU pragma: export
#include "argil/core/hierarchy/normal_cone.hpp"           // IWYU pragma: export
#include "argil/core/hierarchy/patch_bound.hpp"           // IWYU pragma: export
#include "argil/core/hierarchy/surface_hierarchy.hpp"     // IWYU pragma: export
// collision
#include "argil/core/collision/broad_phase.hpp"            // IWYU pragma: export
#include "argil/core/collision/contact.hpp"                // IWYU pragma: export
#include "argil/core/collision/implicit_contact.hpp"       // IWYU pragma: export
#include "argil/core/collision/scene_collision.hpp"        // IWYU pragma: export
#include "argil/core/collision/surface_contact.hpp"        // IWYU pragma: export
#include "argil/core/collision/surface_intersection.hpp"   // IWYU pragma: export
#include "argil/core/collision/surface_penetration.hpp"    // IWYU pragma: export
#include "argil/core/collision/triangle_intersection.hpp"  // IWYU pragma: export
#include "argil/core/collision/trimmed_contact.hpp"        // IWYU pragma: export
// deform
#include "argil/core/deform/contact_footprint.hpp"    // IWYU pragma: export
#include "argil/core/deform/contact_response.hpp"     // IWYU pragma: export
#include "argil/core/deform/deformable_body.hpp"      // IWYU pragma: export
#include "argil/core/deform/edge_joint.hpp"           // IWYU pragma: export
#include "argil/core/deform/join_rows.hpp"            // IWYU pragma: export
#include "argil/core/deform/material.hpp"             // IWYU pragma: export
#include "argil/core/deform/pole_stencil_matrix.hpp"  // IWYU pragma: export
#include "argil/core/deform/pole_window.hpp"          // IWYU pragma: export
#include "argil/core/deform/shell_matrices.hpp"       // IWYU pragma: export
// haptic
#include "argil/core/haptic/device_sample.hpp"       // IWYU pragma: export
#include "argil/core/haptic/haptic_tick.hpp"         // IWYU pragma: export
#include "argil/core/haptic/sphere_proxy.hpp"        // IWYU pragma: export
#include "argil/core/haptic/surface_tool_proxy.hpp"  // IWYU pragma: export
#include "argil/core/haptic/virtual_coupling.hpp"    // IWYU pragma: export
