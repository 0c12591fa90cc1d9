#pragma once
// The reference curves bench_intersection measures every peer against, from
// code none of the peers share.
// - Graph pairs (both surfaces z over the same (x, y) square, x a function of
//   u alone and y of v alone): brute force. z_a - z_b is sampled on a dense
//   (x, y) grid with OpenCASCADE's evaluator, every grid edge where it
//   changes sign is solved to rounding, and the crossing cells are joined
//   into connected components (the true curve count, at the grid's
//   resolution).
// - Other pairs: OpenCASCADE GeomInt_IntSS at 1e-10 of the size, its lines
//   sampled densely and joined where their ends meet.

#include <string>
#include <vector>

#include "argil/core/geometry/bspline_surface.hpp"
#include "intersection_peers.hpp"

namespace argil::bench {

struct OracleCurves {
  std::vector<Eigen::Vector3d> samples;  // points on the true intersection [mm]
  int components = 0;                    // the true number of curves
  double residual = 0.0;  // the samples' largest distance to either surface [mm] (OCCT)
  std::string method;
};

/// Brute force over a grid x grid sampling of the common (x, y) square.
OracleCurves graph_oracle(const BSplineSurface& a, const BSplineSurface& b, int grid);

/// OpenCASCADE's own intersection at a tight tolerance.
OracleCurves occt_oracle(const BSplineSurface& a, const BSplineSurface& b, double size);

}  // namespace argil::bench
