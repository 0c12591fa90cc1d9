#include "argil/core/collision/detail/swept_leaves.hpp"

#include <initializer_list>

namespace argil::detail {

namespace {

/// Corner indices of a leaf's triangles (see LeafCorners).
constexpr std::array<std::array<int, 3>, 2> kTriangleCorners{{{0, 1, 3}, {0, 3, 2}}};

Triangle triangle_of(const LeafCorners& c, int t) {
  const auto& k = kTriangleCorners[static_cast<std::size_t>(t)];
  return {c[static_cast<std::size_t>(k[0])], c[static_cast<std::size_t>(k[1])],
          c[static_cast<std::size_t>(k[2])]};
}

/// True when every point lies strictly on one side of the triangle's plane.
bool one_side(const Triangle& plane, std::initializer_list<const Triangle*> points) {
  int side = 0;
  for (const Triangle* t : points)
    for (const Eigen::Vector3d& x : *t) {
      const int s = orient3d(plane[0], plane[1], plane[2], x).sign;
      if (s == 0 || (side != 0 && s != side)) return false;
      side = s;
    }
  return true;
}

/// Where segment [p, q] meets triangle t (touching counts), by the signs of
/// exact-sign orientation predicates.
std::optional<Eigen::Vector3d> segment_meets(const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                                             const Triangle& t) {
  const Orientation op = orient3d(t[0], t[1], t[2], p);
  const Orientation oq = orient3d(t[0], t[1], t[2], q);
  if (op.sign == oq.sign && op.sign != 0) return std::nullopt;
  if (op.sign == 0 && oq.sign == 0) {
    // In the plane: a degenerate triangle's closest features decide.
    const TriangleDistance d = triangle_distance(t, Triangle{p, q, q});
    if (d.distance > 0.0) return std::nullopt;
    return d.point_a;
  }
  const int s0 = orient3d(p, q, t[0], t[1]).sign;
  const int s1 = orient3d(p, q, t[1], t[2]).sign;
  const int s2 = orient3d(p, q, t[2], t[0]).sign;
  if ((s0 > 0 || s1 > 0 || s2 > 0) && (s0 < 0 || s1 < 0 || s2 < 0)) return std::nullopt;
  const double lambda = op.value == oq.value ? 0.0 : op.value / (op.value - oq.value);
  return Eigen::Vector3d(p + lambda * (q - p));
}

/// Where a moving triangle met a fixed one: the point, and the moving
/// triangle's barycentric coordinates of its point that was there.
struct MovingHit {
  Eigen::Vector3d point, bary_moving;
};

Eigen::Vector3d unit(std::size_t k) { return Eigen::Vector3d::Unit(static_cast<Eigen::Index>(k)); }

/// Triangle s (fixed) against triangle t moving from t0 to t1; a's view only.
std::optional<MovingHit> moving_meets_fixed(const Triangle& s, const Triangle& t0,
                                            const Triangle& t1) {
  for (std::size_t i = 0; i < 3; ++i) {
    // A corner's path through s.
    if (std::optional<Eigen::Vector3d> x = segment_meets(t0[i], t1[i], s))
      return MovingHit{*x, unit(i)};
    // The quad an edge sweeps, as two triangles: (t0[i], t0[j], t1[j]) and
    // (t0[i], t1[j], t1[i]). The weight on j's corners is how far along the
    // edge the point that met s lies.
    const std::size_t j = (i + 1) % 3;
    for (int half = 0; half < 2; ++half) {
      const Triangle quad =
          half == 0 ? Triangle{t0[i], t0[j], t1[j]} : Triangle{t0[i], t1[j], t1[i]};
      const TriangleIntersection x = intersect_triangles(s, quad);
      if (x.kind == TriangleIntersection::Kind::none) continue;
      const Eigen::Vector3d& w = x.bary_b[0];
      const double along = half == 0 ? w[1] + w[2] : w[1];
      return MovingHit{x.points[0], (1.0 - along) * unit(i) + along * unit(j)};
    }
  }
  return std::nullopt;
}

}  // namespace

std::array<Triangle, 2> leaf_triangles_of(const LeafCorners& c) {
  return {triangle_of(c, 0), triangle_of(c, 1)};
}

std::optional<SweptHit> swept_leaves_meet(const SweptLeafPair& pair) {
  for (int i = 0; i < 2; ++i) {
    const Triangle s = triangle_of(pair.a, i);
    const Triangle s0 = triangle_of(pair.a_in_b_start, i);
    const Triangle s1 = triangle_of(pair.a_in_b_end, i);
    for (int j = 0; j < 2; ++j) {
      const Triangle t0 = triangle_of(pair.b_start, j);
      const Triangle t1 = triangle_of(pair.b_end, j);
      const Triangle t_own = triangle_of(pair.b_own, j);
      if (one_side(s, {&t0, &t1}) || one_side(t_own, {&s0, &s1})) continue;
      if (std::optional<MovingHit> x = moving_meets_fixed(s, t0, t1))
        return SweptHit{x->point, i, barycentric(x->point, s), j, x->bary_moving};
      // Seen from b: a corner of a passing through b's triangle.
      for (std::size_t k = 0; k < 3; ++k)
        if (std::optional<Eigen::Vector3d> on_b = segment_meets(s0[k], s1[k], t_own))
          return SweptHit{s[k], i, unit(k), j, barycentric(*on_b, t_own)};
    }
  }
  return std::nullopt;
}

}  // namespace argil::detail
