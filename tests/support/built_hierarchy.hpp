#pragma once
// A surface's hierarchy for a test, built with an operator cache shared by all
// calls; a surface the builder refuses fails the test with its message.

#include <stdexcept>
#include <utility>

#include "argil/core.hpp"

namespace argil::test {

inline SurfaceHierarchy hierarchy_for(const BSplineSurface& s) {
  static OperatorCache cache;
  Result<SurfaceHierarchy> h = SurfaceHierarchy::build(s, cache);
  if (!h.ok()) throw std::runtime_error("hierarchy refused the surface: " + h.status().message);
  return std::move(h).value();
}

}  // namespace argil::test
