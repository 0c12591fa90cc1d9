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

namespace {

/// A triangle's corners, edges and the dot products of its edges: what the
/// six corner-face and nine edge-edge tests of triangle_distance share, so
/// each test computes only the dot products that involve the other triangle.
struct TriangleFrame {
  explicit TriangleFrame(const Triangle& t) : corner(t) {
    for (std::size_t k = 0; k < 3; ++k) {
      edge[k] = t[(k + 1) % 3] - t[k];
      edge_squared[k] = edge[k].squaredNorm();
    }
    ac = t[2] - t[0];
    ab_ac = edge[0].dot(ac);
    ac_ac = ac.squaredNorm();
  }
  const Triangle& corner;
  std::array<Eigen::Vector3d, 3> edge;  // edge k runs from corner k to k + 1
  std::array<double, 3> edge_squared;
  Eigen::Vector3d ac;  // corner 0 to corner 2 (-edge[2])
  double ab_ac, ac_ac;
};

/// Barycentric weights of the triangle's point nearest q (Ericson 5.1.5). Of
/// its six dot products four follow from the first two and the triangle's
/// own: with p = q - a, b - a = ab and c - a = ac, ab.(q - b) = ab.p - ab.ab,
/// and so on.
Eigen::Vector3d nearest_weights(const TriangleFrame& t, const Eigen::Vector3d& q) {
  const Eigen::Vector3d ap = q - t.corner[0];
  const double d1 = t.edge[0].dot(ap), d2 = t.ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
  const double d3 = d1 - t.edge_squared[0], d4 = d2 - t.ab_ac;
  if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return {1 - v, v, 0};
  }
  const double d5 = d1 - t.ab_ac, d6 = d2 - t.ac_ac;
  if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return {1 - w, 0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0, 1 - w, w};
  }
  const double sum = va + vb + vc;
  // Degenerate (collinear) triangle: the general search picks its nearest edge.
  if (!(sum > 0)) return barycentric(q, t.corner);
  const double v = vb / sum, w = vc / sum;
  return {1 - v - w, v, w};
}

/// Parameters (s, t) of the closest points of edge i of a and edge j of b.
SegmentParameters nearest_on_edges(const TriangleFrame& a, std::size_t i, const TriangleFrame& b,
                                   std::size_t j) {
  return closest_on_segments(a.edge[i], a.edge_squared[i], b.edge[j], b.edge_squared[j],
                             a.corner[i] - b.corner[j]);
}

}  // namespace

TriangleDistance triangle_distance(const Triangle& a, const Triangle& b) {
  // The haptic tick's contact queries spend a fifth of their time here (a
  // tool lying on a face has its leaves within eps of several of the face's
  // each), hence the shared frames.
  const TriangleFrame fa(a), fb(b);
  TriangleDistance best;
  double best_squared = std::numeric_limits<double>::infinity();
  const auto consider = [&](const Eigen::Vector3d& pa, const Eigen::Vector3d& pb,
                            const Eigen::Vector3d& wa, const Eigen::Vector3d& wb) {
    const double d = (pa - pb).squaredNorm();
    if (!(d < best_squared)) return;
    best_squared = d;
    best = {0.0, pa, pb, wa, wb};
  };
  for (std::size_t k = 0; k < 3; ++k) {
    const Eigen::Vector3d wb = nearest_weights(fb, a[k]);
    consider(a[k], point_of(b, wb), Eigen::Vector3d::Unit(static_cast<int>(k)), wb);
    const Eigen::Vector3d wa = nearest_weights(fa, b[k]);
    consider(point_of(a, wa), b[k], wa, Eigen::Vector3d::Unit(static_cast<int>(k)));
  }
  for (std::size_t i = 0; i < 3; ++i) {
    const std::size_t i1 = (i + 1) % 3;
    for (std::size_t j = 0; j < 3; ++j) {
      const std::size_t j1 = (j + 1) % 3;
      const auto [s, t] = nearest_on_edges(fa, i, fb, j);
      Eigen::Vector3d wa = Eigen::Vector3d::Zero(), wb = Eigen::Vector3d::Zero();
      wa[static_cast<int>(i)] = 1.0 - s;
      wa[static_cast<int>(i1)] = s;
      wb[static_cast<int>(j)] = 1.0 - t;
      wb[static_cast<int>(j1)] = t;
      consider(a[i] + s * fa.edge[i], b[j] + t * fb.edge[j], wa, wb);
    }
  }
  best.distance = std::sqrt(best_squared);
  return best;
}

}  // namespace argil
