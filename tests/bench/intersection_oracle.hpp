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

#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <Geom_BSplineSurface.hxx>

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

/// A graph surface: x a function of u alone, y of v alone, inverted per axis
/// by bisection (x(u) and y(v) are monotone).
struct GraphSurface {
  Handle(Geom_BSplineSurface) s;
  double u0 = 0, u1 = 0, v0 = 0, v1 = 0;
  explicit GraphSurface(const BSplineSurface& surface);
  /// The parameter along `axis` (0: u, for x; 1: v, for y) where the
  /// coordinate reaches `value`.
  double invert(int axis, double value) const;
};

/// The largest distance of points to either of two surfaces, each distance
/// by OpenCASCADE projection and, for graph surfaces, also bounded by the
/// vertical gap |z - z_s(x, y)| (the smaller of the two bounds is kept):
/// OpenCASCADE's projection can stop at a local minimum on a surface with C0
/// creases (degree 1, full-multiplicity knots). At most 2000 points, evenly
/// spread, are measured.
class SurfaceDistance {
 public:
  SurfaceDistance(const BSplineSurface& a, const BSplineSurface& b, bool graphs);
  double worst(const std::vector<Polyline>& lines);

 private:
  double to(int side, const Eigen::Vector3d& p);
  GeomAPI_ProjectPointOnSurf project_[2];
  std::vector<GraphSurface> graphs_;
};

/// Brute force over a grid x grid sampling of the common (x, y) square. With
/// `samples` false only the curve count: no crossing is solved.
OracleCurves graph_oracle(const BSplineSurface& a, const BSplineSurface& b, int grid,
                          bool samples = true);

/// OpenCASCADE's own intersection at a tight tolerance.
OracleCurves occt_oracle(const BSplineSurface& a, const BSplineSurface& b, double size);

}  // namespace argil::bench
