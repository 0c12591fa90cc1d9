#pragma once
// argil::core entry header: surfaces, evaluation and the precomputed operators.

#include "argil/core/banded_lu.hpp"
#include "argil/core/basis.hpp"
#include "argil/core/bezier.hpp"
#include "argil/core/bspline_surface.hpp"
#include "argil/core/curve_operators.hpp"
#include "argil/core/evaluate.hpp"
#include "argil/core/knot_insertion.hpp"
#include "argil/core/status.hpp"
#include "argil/core/surface_operators.hpp"
