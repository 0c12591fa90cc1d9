#pragma once
// argil::core entry header: surfaces, evaluation, precomputed operators, the
// conservative hierarchy and collision queries.

#include "argil/core/banded_lu.hpp"
#include "argil/core/basis.hpp"
#include "argil/core/bezier.hpp"
#include "argil/core/broad_phase.hpp"
#include "argil/core/bspline_surface.hpp"
#include "argil/core/contact.hpp"
#include "argil/core/contact_regions.hpp"
#include "argil/core/curve_operators.hpp"
#include "argil/core/evaluate.hpp"
#include "argil/core/implicit_contact.hpp"
#include "argil/core/implicit_tool.hpp"
#include "argil/core/knot_insertion.hpp"
#include "argil/core/patch_bound.hpp"
#include "argil/core/scene_collision.hpp"
#include "argil/core/status.hpp"
#include "argil/core/surface_hierarchy.hpp"
#include "argil/core/surface_intersection.hpp"
#include "argil/core/surface_operators.hpp"
#include "argil/core/surface_penetration.hpp"
#include "argil/core/triangle_intersection.hpp"
