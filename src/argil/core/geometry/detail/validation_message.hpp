#pragma once
// Builds a validation result whose message names the field, index and value.

#include <sstream>

#include "argil/core/geometry/bspline_surface.hpp"

namespace argil::detail {

/// The defect with its message: the parts streamed in order, numbers with 17
/// significant digits so the message reproduces the input.
template <class... Parts>
SurfaceValidation defect(SurfaceDefect d, const Parts&... parts) {
  std::ostringstream text;
  text.precision(17);
  (text << ... << parts);
  return {d, text.str()};
}

}  // namespace argil::detail
