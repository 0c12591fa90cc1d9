#pragma once
// Bounds that prove an edge curve of one Bezier patch crosses another patch at
// most once: what lets a surface-surface query account for every end of the
// intersection arcs inside a transversal node pair.

#include <Eigen/Core>

#include "argil/core/geometry/bezier.hpp"

namespace argil {

/// The four edge curves of a patch over [0, 1]^2, in the order of its corner
/// ring c00, c10, c11, c01: t = 0, s = 1, t = 1, s = 0.
enum class PatchEdge { t0, s1, t1, s0 };

/// An upper bound on |axis . w| / |w| over every chord w = S(p2) - S(p1) of a
/// polynomial patch (unit `axis`); 1 or more when no bound below 1 holds.
/// A chord is the integral of S_s ds + S_t dt along the straight path between
/// p1 and p2, so it is a positive combination of the net's s differences of
/// one sign and its t differences of one sign; the bound is the largest lean
/// of those differences out of the plane normal to `axis` over the smallest
/// share any of them has along the combination's middle direction.
double chord_lean(const BezierPatch& patch, const Eigen::Vector3d& axis);

/// The least |axis . e| over the unit directions e of an edge curve's net
/// differences when they all lie strictly on one side of the plane normal to
/// `axis` (unit), else 0. Every chord of the edge curve is a positive
/// combination of them, so it leans at least this far out of that plane.
double edge_rise(const BezierPatch& patch, PatchEdge edge, const Eigen::Vector3d& axis);

/// An edge curve whose rise exceeds the other patch's chord lean along the
/// same axis meets that patch at most once: two meeting points would make a
/// chord of both. The margin covers the rounding of both bounds (a few ulps
/// of numbers below 1).
inline bool crosses_at_most_once(double edge_rise, double chord_lean) {
  return edge_rise > chord_lean + 1e-12;
}

}  // namespace argil
