#pragma once
// Repeated point-and-derivative evaluation of one surface through the Bezier
// patches of its elements: no knot search and no basis recurrence with
// divisions per call, for the many evaluations of a Newton iteration that
// stay in a few elements.

#include <array>

#include "argil/core/geometry/bezier.hpp"
#include "argil/core/geometry/bspline_surface.hpp"
#include "argil/core/operators/surface_operators.hpp"

namespace argil {

/// Evaluates `surface` as evaluate_derivatives(surface, u, v, order) does, with
/// the same element (span) choice at knots, so one-sided derivatives at a
/// knot of reduced continuity are the same ones; values agree to rounding
/// (the Bezier net is the span's poles through its extraction operators).
/// Keeps the patches of the last few elements used. Holds references: the
/// surface and operators must outlive it, and its control points must not
/// change while it is used. Not for sharing between threads.
class PatchEvaluator {
 public:
  /// Precondition: `ops` are the operators of the surface's degree and knots.
  PatchEvaluator(const BSplineSurface& surface, const SurfaceOperators& ops);

  const BSplineSurface& surface() const { return surface_; }

  /// Point, and with order 1 the first partial derivatives per unit of u
  /// and v [mm], at (u, v) clamped to the domain. Order 2 is passed on to
  /// evaluate_derivatives: through a short span's Bezier net second
  /// derivatives lose digits (1e-11 of their terms' size against OpenCASCADE
  /// on non-uniform knots, where evaluate_derivatives keeps 3e-13).
  SurfaceDerivatives evaluate(double u, double v, int order);

 private:
  /// One direction's element around t (the span find_span gives) and t's
  /// place in it: local s in [0, 1] and 1 / the span's length.
  struct Place {
    int element = 0;
    double s = 0.0;
    double inverse_length = 0.0;
  };
  Place place(Direction d, double t, int last_element) const;

  struct Slot {
    int element_u = -1, element_v = -1;
    BezierPatch patch;
  };
  const BezierPatch& patch(int element_u, int element_v);

  const BSplineSurface& surface_;
  const SurfaceOperators& ops_;
  /// Few slots: a Newton iteration or a curve's run of points crosses an
  /// element edge now and then, and steps back across it.
  static constexpr int kSlots = 4;
  std::array<Slot, kSlots> slots_;
  int next_slot_ = 0;
  int last_u_ = 0, last_v_ = 0;  // the elements of the last call, tried first
};

}  // namespace argil
