#pragma once
// Internal to argil_io: a closed surface's domain moved to where its face
// wraps, so that every trim lies inside it.

#include <Geom_BSplineSurface.hxx>
#include <TopoDS_Face.hxx>

namespace argil::io::detail {

/// `surface` (the B-spline under `face`) with each closed direction's domain
/// [o, o + period] starting where the face wraps: at its seam edge, else in the
/// middle of the band the face leaves out. The same surface where the domain
/// already holds the face, or where the face spans more than a period.
///
/// Why: OpenCASCADE's NURBS conversion of a cylinder or torus cuts the circle
/// at a parameter that is not the seam's angle, and its face then runs past
/// the domain's end, kept only by extrapolation (11752.stp: 13 faces, by up to
/// 0.6% of the circle). A closed surface is the same surface periodically, so
/// moving its origin keeps the surface (to rounding) and the pcurves.
Handle(Geom_BSplineSurface)
    seated_on_face(const Handle(Geom_BSplineSurface) & surface, const TopoDS_Face& face);

}  // namespace argil::io::detail
