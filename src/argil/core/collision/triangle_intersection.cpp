#include "argil/core/collision/triangle_intersection.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "argil/core/geometry/triangle_distance.hpp"

namespace argil {

namespace {

constexpr double kUnitRoundoff = std::numeric_limits<double>::epsilon() / 2;  // 2^-53

/// Points where a triangle meets the other triangle's plane, with their
/// barycentric coordinates: one or two points (three only when coplanar).
struct PlaneCut {
  int count = 0;
  std::array<Eigen::Vector3d, 3> points;
  std::array<Eigen::Vector3d, 3> bary;
};

PlaneCut cut_by_plane(const Triangle& t, const std::array<Orientation, 3>& side) {
  PlaneCut cut;
  for (int i = 0; i < 3; ++i) {
    if (side[static_cast<std::size_t>(i)].sign == 0) {
      cut.points[static_cast<std::size_t>(cut.count)] = t[static_cast<std::size_t>(i)];
      cut.bary[static_cast<std::size_t>(cut.count)] = Eigen::Vector3d::Unit(i);
      ++cut.count;
    }
  }
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    const Orientation& si = side[static_cast<std::size_t>(i)];
    const Orientation& sj = side[static_cast<std::size_t>(j)];
    if (si.sign * sj.sign >= 0) continue;
    // The determinants are signed distances times one common factor, so the
    // crossing is at the same fraction of the edge.
    const double lambda = si.value / (si.value - sj.value);
    const auto& pi = t[static_cast<std::size_t>(i)];
    const auto& pj = t[static_cast<std::size_t>(j)];
    cut.points[static_cast<std::size_t>(cut.count)] = pi + lambda * (pj - pi);
    Eigen::Vector3d b = Eigen::Vector3d::Zero();
    b[i] = 1.0 - lambda;
    b[j] = lambda;
    cut.bary[static_cast<std::size_t>(cut.count)] = b;
    ++cut.count;
  }
  return cut;
}

/// 2D coordinates in the plane that drops the normal's largest axis.
Eigen::Vector2d drop_axis(const Eigen::Vector3d& p, int axis) {
  return axis == 0 ? Eigen::Vector2d(p.y(), p.z())
                   : (axis == 1 ? Eigen::Vector2d(p.z(), p.x()) : Eigen::Vector2d(p.x(), p.y()));
}

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// Overlap of coplanar triangles: a clipped by b's three edge half-planes
/// (Sutherland-Hodgman, boundary inclusive), reported at the polygon's centroid.
TriangleIntersection coplanar_overlap(const Triangle& a, const Triangle& b) {
  TriangleIntersection out;
  const Eigen::Vector3d na = (a[1] - a[0]).cross(a[2] - a[0]);
  const Eigen::Vector3d nb = (b[1] - b[0]).cross(b[2] - b[0]);
  const Eigen::Vector3d n = na.squaredNorm() >= nb.squaredNorm() ? na : nb;
  int axis = 0;
  n.cwiseAbs().maxCoeff(&axis);
  std::array<Eigen::Vector2d, 3> b2;
  for (std::size_t k = 0; k < 3; ++k) b2[k] = drop_axis(b[k], axis);
  const double area_b = cross2(b2[1] - b2[0], b2[2] - b2[0]);
  if (area_b == 0.0) return out;  // b is a segment in this projection: no area to share
  const double orientation = area_b > 0 ? 1.0 : -1.0;
  std::vector<Eigen::Vector3d> polygon(a.begin(), a.end());
  std::vector<Eigen::Vector3d> next;
  for (std::size_t e = 0; e < 3 && !polygon.empty(); ++e) {
    const Eigen::Vector2d& p = b2[e];
    const Eigen::Vector2d& q = b2[(e + 1) % 3];
    const auto side = [&](const Eigen::Vector3d& x) {
      return orientation * cross2(q - p, drop_axis(x, axis) - p);
    };
    next.clear();
    for (std::size_t k = 0; k < polygon.size(); ++k) {
      const Eigen::Vector3d& x = polygon[k];
      const Eigen::Vector3d& y = polygon[(k + 1) % polygon.size()];
      const double sx = side(x), sy = side(y);
      if (sx >= 0) next.push_back(x);
      if ((sx > 0 && sy < 0) || (sx < 0 && sy > 0)) next.push_back(x + (y - x) * (sx / (sx - sy)));
    }
    polygon.swap(next);
  }
  if (polygon.empty()) return out;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& x : polygon) centroid += x;
  centroid /= static_cast<double>(polygon.size());
  out.kind = TriangleIntersection::Kind::coplanar;
  out.points = {centroid, centroid};
  const Eigen::Vector3d ba = barycentric(centroid, a), bb = barycentric(centroid, b);
  out.bary_a = {ba, ba};
  out.bary_b = {bb, bb};
  return out;
}

}  // namespace

Orientation orient3d(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                     const Eigen::Vector3d& d) {
  // Shewchuk's orient3d on differences to d, with its static error bound
  // (Adaptive Precision Floating-Point Arithmetic, 1997): a determinant whose
  // magnitude exceeds the bound has the sign of the exact one.
  const Eigen::Vector3d ad = a - d, bd = b - d, cd = c - d;
  const double bc_yz = bd.y() * cd.z(), cb_yz = bd.z() * cd.y();
  const double ca_yz = cd.y() * ad.z(), ac_yz = cd.z() * ad.y();
  const double ab_yz = ad.y() * bd.z(), ba_yz = ad.z() * bd.y();
  const double det = ad.x() * (bc_yz - cb_yz) + bd.x() * (ca_yz - ac_yz) + cd.x() * (ab_yz - ba_yz);
  const double permanent = (std::abs(bc_yz) + std::abs(cb_yz)) * std::abs(ad.x()) +
                           (std::abs(ca_yz) + std::abs(ac_yz)) * std::abs(bd.x()) +
                           (std::abs(ab_yz) + std::abs(ba_yz)) * std::abs(cd.x());
  const double bound = (7.0 + 56.0 * kUnitRoundoff) * kUnitRoundoff * permanent;
  // Shewchuk's determinant is positive below the plane; ours is positive on
  // the side (b - a) x (c - a) points to.
  Orientation o;
  if (det > bound) {
    o = {-1, -det};
  } else if (det < -bound) {
    o = {1, -det};
  }
  return o;
}

namespace {

/// Direction to compare two plane cuts along: the planes' common line, or the
/// longer cut when the planes are too close to parallel to give a line;
/// nullopt for two single points (touching is left to the distance test).
std::optional<Eigen::Vector3d> common_axis(const Triangle& a, const Triangle& b,
                                           const PlaneCut& cut_a, const PlaneCut& cut_b) {
  const Eigen::Vector3d na = (a[1] - a[0]).cross(a[2] - a[0]);
  const Eigen::Vector3d nb = (b[1] - b[0]).cross(b[2] - b[0]);
  const Eigen::Vector3d axis = na.cross(nb);
  if (axis.squaredNorm() > 1e-24 * na.squaredNorm() * nb.squaredNorm()) return axis;
  const Eigen::Vector3d da =
      cut_a.points[static_cast<std::size_t>(cut_a.count - 1)] - cut_a.points[0];
  const Eigen::Vector3d db =
      cut_b.points[static_cast<std::size_t>(cut_b.count - 1)] - cut_b.points[0];
  const Eigen::Vector3d longer = da.squaredNorm() >= db.squaredNorm() ? da : db;
  if (longer.squaredNorm() == 0.0) return std::nullopt;
  return longer;
}

/// A cut's end points ordered along the axis, with their axis values.
struct CutInterval {
  int lo = 0, hi = 0;     // indices into the cut's points
  double t0 = 0, t1 = 0;  // axis values of lo and hi
  /// Barycentric coordinates of the point at axis value x on the cut.
  Eigen::Vector3d at(const PlaneCut& c, double x) const {
    const double f = t1 > t0 ? std::clamp((x - t0) / (t1 - t0), 0.0, 1.0) : 0.0;
    return Eigen::Vector3d((1.0 - f) * c.bary[static_cast<std::size_t>(lo)] +
                           f * c.bary[static_cast<std::size_t>(hi)]);
  }
};

CutInterval interval_along(const PlaneCut& c, const Eigen::Vector3d& axis) {
  CutInterval i{0, c.count - 1, 0.0, 0.0};
  if (axis.dot(c.points[static_cast<std::size_t>(i.hi)]) <
      axis.dot(c.points[static_cast<std::size_t>(i.lo)]))
    std::swap(i.lo, i.hi);
  i.t0 = axis.dot(c.points[static_cast<std::size_t>(i.lo)]);
  i.t1 = axis.dot(c.points[static_cast<std::size_t>(i.hi)]);
  return i;
}

Eigen::Vector3d point_of(const Triangle& t, const Eigen::Vector3d& w) {
  return Eigen::Vector3d(w[0] * t[0] + w[1] * t[1] + w[2] * t[2]);
}

/// The overlap of the two cuts along the axis: lower end the later start of
/// the two, upper end the earlier finish; none when they do not overlap.
TriangleIntersection overlap_of_cuts(const Triangle& a, const Triangle& b, const PlaneCut& cut_a,
                                     const PlaneCut& cut_b, const Eigen::Vector3d& axis) {
  TriangleIntersection out;
  const CutInterval ia = interval_along(cut_a, axis);
  const CutInterval ib = interval_along(cut_b, axis);
  if (ia.t1 < ib.t0 || ib.t1 < ia.t0) return out;
  out.kind = TriangleIntersection::Kind::segment;
  if (ia.t0 >= ib.t0) {
    out.bary_a[0] = cut_a.bary[static_cast<std::size_t>(ia.lo)];
    out.bary_b[0] = ib.at(cut_b, ia.t0);
  } else {
    out.bary_b[0] = cut_b.bary[static_cast<std::size_t>(ib.lo)];
    out.bary_a[0] = ia.at(cut_a, ib.t0);
  }
  if (ia.t1 <= ib.t1) {
    out.bary_a[1] = cut_a.bary[static_cast<std::size_t>(ia.hi)];
    out.bary_b[1] = ib.at(cut_b, ia.t1);
  } else {
    out.bary_b[1] = cut_b.bary[static_cast<std::size_t>(ib.hi)];
    out.bary_a[1] = ia.at(cut_a, ib.t1);
  }
  for (std::size_t k = 0; k < 2; ++k) {
    // Both evaluations lie on the common line; their mean splits the rounding.
    out.points[k] = 0.5 * (point_of(a, out.bary_a[k]) + point_of(b, out.bary_b[k]));
  }
  return out;
}

}  // namespace

namespace {

/// Corners within `on_plane` of the plane count as on it; the determinant is
/// the corner's distance times the plane triangle's doubled area.
void snap_to_plane(const Triangle& plane, double on_plane, std::array<Orientation, 3>& side) {
  if (!(on_plane > 0.0)) return;
  const double scale = (plane[1] - plane[0]).cross(plane[2] - plane[0]).norm();
  for (Orientation& o : side) {
    if (std::abs(o.value) <= on_plane * scale) o = {};
  }
}

}  // namespace

TriangleIntersection intersect_triangles(const Triangle& a, const Triangle& b, double on_plane) {
  std::array<Orientation, 3> side_a, side_b;  // corners of a against plane b, and back
  for (std::size_t k = 0; k < 3; ++k) side_a[k] = orient3d(b[0], b[1], b[2], a[k]);
  snap_to_plane(b, on_plane, side_a);
  const auto all_same = [](const std::array<Orientation, 3>& s) {
    return (s[0].sign > 0 && s[1].sign > 0 && s[2].sign > 0) ||
           (s[0].sign < 0 && s[1].sign < 0 && s[2].sign < 0);
  };
  const auto all_zero = [](const std::array<Orientation, 3>& s) {
    return s[0].sign == 0 && s[1].sign == 0 && s[2].sign == 0;
  };
  if (all_same(side_a)) return {};
  for (std::size_t k = 0; k < 3; ++k) side_b[k] = orient3d(a[0], a[1], a[2], b[k]);
  snap_to_plane(a, on_plane, side_b);
  if (all_same(side_b)) return {};
  if (all_zero(side_a) || all_zero(side_b)) return coplanar_overlap(a, b);
  const PlaneCut cut_a = cut_by_plane(a, side_a);
  const PlaneCut cut_b = cut_by_plane(b, side_b);
  if (cut_a.count == 0 || cut_b.count == 0) return {};
  // Both cuts lie on the planes' common line; compare them along it.
  const std::optional<Eigen::Vector3d> axis = common_axis(a, b, cut_a, cut_b);
  if (!axis) return {};
  return overlap_of_cuts(a, b, cut_a, cut_b, *axis);
}

Eigen::Vector3d barycentric(const Eigen::Vector3d& p, const Triangle& t) {
  const Eigen::Vector3d q = closest_point_on_triangle(p, t[0], t[1], t[2]);
  const Eigen::Vector3d v0 = t[1] - t[0], v1 = t[2] - t[0], v2 = q - t[0];
  const double d00 = v0.dot(v0), d01 = v0.dot(v1), d11 = v1.dot(v1);
  const double d20 = v2.dot(v0), d21 = v2.dot(v1);
  const double denom = d00 * d11 - d01 * d01;
  if (!(denom > 1e-30 * std::max(d00 * d11, std::numeric_limits<double>::min()))) {
    int best = 0;
    double best_d = (p - t[0]).squaredNorm();
    for (int k = 1; k < 3; ++k) {
      const double d = (p - t[static_cast<std::size_t>(k)]).squaredNorm();
      if (d < best_d) {
        best_d = d;
        best = k;
      }
    }
    return Eigen::Vector3d::Unit(best);
  }
  const double v = (d11 * d20 - d01 * d21) / denom;
  const double w = (d00 * d21 - d01 * d20) / denom;
  Eigen::Vector3d b(1.0 - v - w, v, w);
  b = b.cwiseMax(0.0);
  return b / b.sum();
}

TriangleDistance triangle_distance(const Triangle& a, const Triangle& b) {
  // Candidates compare by squared distance; a corner's foot on the other
  // triangle gets its barycentric coordinates only if it wins (they cost a
  // second closest-point search).
  enum class Foot { none, on_a, on_b };
  TriangleDistance best;
  double best_squared = std::numeric_limits<double>::infinity();
  Foot foot = Foot::none;
  const auto consider = [&](const Eigen::Vector3d& pa, const Eigen::Vector3d& pb,
                            const Eigen::Vector3d& wa, const Eigen::Vector3d& wb, Foot f) {
    const double d = (pa - pb).squaredNorm();
    if (!(d < best_squared)) return;
    best_squared = d;
    best = {0.0, pa, pb, wa, wb};
    foot = f;
  };
  const Eigen::Vector3d unknown = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d& pa = a[static_cast<std::size_t>(k)];
    consider(pa, closest_point_on_triangle(pa, b[0], b[1], b[2]), Eigen::Vector3d::Unit(k), unknown,
             Foot::on_b);
    const Eigen::Vector3d& pb = b[static_cast<std::size_t>(k)];
    consider(closest_point_on_triangle(pb, a[0], a[1], a[2]), pb, unknown, Eigen::Vector3d::Unit(k),
             Foot::on_a);
  }
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3;
      const auto& p0 = a[static_cast<std::size_t>(i)];
      const auto& p1 = a[static_cast<std::size_t>(i1)];
      const auto& q0 = b[static_cast<std::size_t>(j)];
      const auto& q1 = b[static_cast<std::size_t>(j1)];
      const auto [s, t] = closest_on_segments(p0, p1, q0, q1);
      Eigen::Vector3d wa = Eigen::Vector3d::Zero(), wb = Eigen::Vector3d::Zero();
      wa[i] = 1.0 - s;
      wa[i1] = s;
      wb[j] = 1.0 - t;
      wb[j1] = t;
      consider(p0 + s * (p1 - p0), q0 + t * (q1 - q0), wa, wb, Foot::none);
    }
  }
  best.distance = std::sqrt(best_squared);
  if (foot == Foot::on_a) best.bary_a = barycentric(best.point_a, a);
  if (foot == Foot::on_b) best.bary_b = barycentric(best.point_b, b);
  return best;
}

}  // namespace argil
