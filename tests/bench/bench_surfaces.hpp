#pragma once
// Surfaces shared by the benchmarks, and their OpenCASCADE copies.

#include <Geom_BSplineSurface.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <gp_Pnt.hxx>

#include <algorithm>
#include <cmath>

#include "argil/core.hpp"
#include "support/occt_surface.hpp"
#include "support/tool_shapes.hpp"

namespace argil::bench {

using test::uniform_knots;

/// A wavy bicubic panel with n x n poles on a 10 mm pitch (n = 32: 310 mm wide).
inline BSplineSurface bicubic_panel(int n) {
  BSplineSurface s;
  s.degree = {3, 3};
  s.knots = {uniform_knots(3, n), uniform_knots(3, n)};
  s.control_points.resize(static_cast<Eigen::Index>(n) * n, 3);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      s.control_points.row(s.pole_index(i, j)) << 10.0 * i, 10.0 * j,
          20.0 * std::sin(0.3 * i) * std::cos(0.2 * j);
  return s;
}

/// The same surface as an OpenCASCADE Geom_BSplineSurface.
inline Handle(Geom_BSplineSurface) to_occt(const BSplineSurface& s) { return test::to_occt(s); }

}  // namespace argil::bench
