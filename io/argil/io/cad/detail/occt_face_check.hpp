#pragma once
// Internal to argil_io: BRepCheck_Analyzer on a built face, its findings named
// by the trim loops and curves they concern.

#include <string>

#include "argil/io/cad/detail/occt_face_builder.hpp"

namespace argil::io::detail {

/// What BRepCheck_Analyzer finds wrong with the face, its wires, edges and
/// vertices, one finding per sub-shape and status, joined by "; ":
/// "loop 0 (wire): BRepCheck_SelfIntersectingWire", "loop 1 curve 2 (edge,
/// tolerance 1e-07 mm): BRepCheck_InvalidCurveOnSurface". Edges not from a trim
/// curve (the sides of an untrimmed face, edges ShapeFix split) are numbered in
/// the face's order ("edge 3"). Empty when the face is valid.
std::string face_defects(const BuiltFace& built);

}  // namespace argil::io::detail
