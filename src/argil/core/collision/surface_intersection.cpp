#include "argil/core/collision/surface_intersection.hpp"

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <tuple>
#include <vector>

#include "argil/core/collision/contact_regions.hpp"
#include "argil/core/collision/surface_penetration.hpp"
#include "argil/core/collision/triangle_intersection.hpp"
#include "argil/core/geometry/evaluate.hpp"
#include "argil/core/geometry/triangle_distance.hpp"

namespace argil {

namespace {

/// A node or a block of elements, copied out of its hierarchy (the node pool
/// may reallocate when children are created).
struct View {
  Eigen::Vector3d center;
  double radius;
  Eigen::Vector3d lo, hi;
  bool flat;
  /// Nodes only: the patch lies within `flatness` of its two corner
  /// triangles (c00, c10, c11), (c00, c11, c01); +inf for blocks.
  double flatness = std::numeric_limits<double>::infinity();
  std::array<Eigen::Vector3d, 4> corners{};
};

/// A lower bound on the distance from anything in `sphere` to the patch of
/// `node`: the sphere centre's distance to the node's corner triangles, less
/// the sphere radius and the node's flatness. Far tighter than the node's own
/// sphere when the patch is nearly flat and wide (a plane against a small
/// tool), where sphere and box tests cannot separate what lies near its plane.
double gap_to_flat_patch(const View& node, const View& sphere) {
  if (!std::isfinite(node.flatness)) return -std::numeric_limits<double>::infinity();
  const auto& c = node.corners;
  const double to_triangles =
      std::min((closest_point_on_triangle(sphere.center, c[0], c[1], c[3]) - sphere.center).norm(),
               (closest_point_on_triangle(sphere.center, c[0], c[3], c[2]) - sphere.center).norm());
  return to_triangles - sphere.radius - node.flatness;
}

/// Entries of one side: blocks as -(id + 1), hierarchy nodes as id >= 0.
class Side {
 public:
  Side(SurfaceHierarchy& h, double flat_tolerance, int max_level, QueryCounters& counters)
      : h_(h), flat_tolerance_(flat_tolerance), max_level_(max_level), counters_(counters) {}

  View view(int entry) {
    if (entry < 0) {
      const PatchBound& b = h_.block(-entry - 1, &counters_).bound;
      return {b.center, b.radius, b.box.min, b.box.max, false};
    }
    const HierarchyNode& n = h_.node(entry, &counters_);
    const PatchBound& b = n.bound;
    // The patch and its corner triangles both lie in the sphere, so they are
    // within 2 r of each other whatever the flatness bound says.
    const bool flat =
        b.flatness <= flat_tolerance_ || 2.0 * b.radius <= flat_tolerance_ || n.level >= max_level_;
    return {b.center, b.radius, b.box.min, b.box.max, flat, b.flatness, b.corners};
  }

  /// Entry of the block's single element, or the block itself.
  int entry_of_block(int block) {
    const ElementBlock& b = h_.block(block);
    return b.element_node >= 0 ? b.element_node : -(block + 1);
  }

  void children(int entry, std::vector<int>& out) {
    out.clear();
    if (entry < 0) {
      const std::array<int, 4> kids = h_.block(-entry - 1).children;
      for (int c : kids)
        if (c >= 0) out.push_back(entry_of_block(c));
      return;
    }
    for (int hu = 0; hu < 2; ++hu)
      for (int hv = 0; hv < 2; ++hv) out.push_back(h_.child(entry, hu, hv));
  }

  SurfaceHierarchy& hierarchy() { return h_; }

 private:
  SurfaceHierarchy& h_;
  double flat_tolerance_;
  int max_level_;
  QueryCounters& counters_;
};

/// The two corner triangles of a flat node and their parameter corners.
struct LeafTriangles {
  std::array<Triangle, 2> triangles;
  std::array<std::array<Eigen::Vector2d, 3>, 2> params;
  double u0, u1, v0, v1;
  double radius;
};

/// True when a cheap lower bound on the distance between the triangles
/// exceeds eps: a gap between their boxes, or one triangle entirely beyond eps
/// on one side of the other's plane.
bool farther_than(const Triangle& a, const Triangle& b, double eps) {
  const auto box_gap = [&](int k) {
    const double a_lo = std::min({a[0][k], a[1][k], a[2][k]});
    const double a_hi = std::max({a[0][k], a[1][k], a[2][k]});
    const double b_lo = std::min({b[0][k], b[1][k], b[2][k]});
    const double b_hi = std::max({b[0][k], b[1][k], b[2][k]});
    return std::max(b_lo - a_hi, a_lo - b_hi);
  };
  if (box_gap(0) > eps || box_gap(1) > eps || box_gap(2) > eps) return true;
  const auto beyond_plane = [eps](const Triangle& t, const Triangle& other) {
    const Eigen::Vector3d n = (t[1] - t[0]).cross(t[2] - t[0]);
    const double length = n.norm();
    if (!(length > 0.0)) return false;
    const double limit = eps * length;
    const double d0 = n.dot(other[0] - t[0]);
    const double d1 = n.dot(other[1] - t[0]);
    const double d2 = n.dot(other[2] - t[0]);
    return std::min({d0, d1, d2}) > limit || std::max({d0, d1, d2}) < -limit;
  };
  return beyond_plane(a, b) || beyond_plane(b, a);
}

/// True when every corner triangle of node a is more than eps + both
/// flatness bounds from every corner triangle of node b (cheap tests only),
/// so the patches are more than eps apart. Separates tilted thin patches
/// that sphere and axis-aligned box tests cannot.
bool triangles_farther_than(const View& a, const View& b, double eps) {
  const double margin = eps + a.flatness + b.flatness;
  const auto& p = a.corners;
  const auto& q = b.corners;
  const std::array<Triangle, 2> ta{Triangle{p[0], p[1], p[3]}, Triangle{p[0], p[3], p[2]}};
  const std::array<Triangle, 2> tb{Triangle{q[0], q[1], q[3]}, Triangle{q[0], q[3], q[2]}};
  for (const Triangle& x : ta)
    for (const Triangle& y : tb)
      if (!farther_than(x, y, margin)) return false;
  return true;
}

/// Adds each crossing region's deepest point of b behind a (if any) to its
/// region: `contacts` are grouped by region, untrimmed.
void add_penetration_contacts(const BSplineSurface& a, const BSplineSurface& b,
                              std::vector<Contact>& contacts) {
  const std::size_t grouped = contacts.size();
  for (std::size_t begin = 0; begin < grouped;) {
    std::size_t end = begin;
    bool crossing = false;
    while (end < grouped && contacts[end].region == contacts[begin].region) {
      crossing = crossing || contacts[end].depth >= 0.0;
      ++end;
    }
    const std::span<const Contact> region(contacts.data() + begin, end - begin);
    const std::optional<Penetration> found =
        crossing ? deepest_penetration(a, b, region) : std::nullopt;
    if (found) {
      const Penetration& deepest = *found;
      Contact c;
      const SurfaceDerivatives d = evaluate_derivatives(a, deepest.uv_a[0], deepest.uv_a[1], 1);
      c.point = d.point;
      c.uv_a = deepest.uv_a;
      c.uv_b = deepest.uv_b;
      c.normal = unit_normal(d);
      c.tangent_u = d.du;
      c.tangent_v = d.dv;
      c.depth = deepest.depth;
      c.region = contacts[begin].region;
      contacts.push_back(c);  // may reallocate: `region` is not used after this
    }
    begin = end;
  }
}

LeafTriangles leaf_triangles(const HierarchyNode& n) {
  const auto& c = n.bound.corners;  // S(0,0), S(1,0), S(0,1), S(1,1)
  const Eigen::Vector2d p00(n.u0, n.v0), p10(n.u1, n.v0), p01(n.u0, n.v1), p11(n.u1, n.v1);
  LeafTriangles t;
  // The same split as PatchBound::flatness: (c00, c10, c11), (c00, c11, c01).
  t.triangles = {Triangle{c[0], c[1], c[3]}, Triangle{c[0], c[3], c[2]}};
  t.params = {std::array<Eigen::Vector2d, 3>{p00, p10, p11},
              std::array<Eigen::Vector2d, 3>{p00, p11, p01}};
  t.u0 = n.u0;
  t.u1 = n.u1;
  t.v0 = n.v0;
  t.v1 = n.v1;
  t.radius = n.bound.radius;
  return t;
}

Eigen::Vector2d param_of(const std::array<Eigen::Vector2d, 3>& p, const Eigen::Vector3d& w) {
  return w[0] * p[0] + w[1] * p[1] + w[2] * p[2];
}

/// One triangle-pair intersection segment with its leaves' parameter sizes.
struct Segment {
  std::array<Eigen::Vector3d, 2> points;
  std::array<Eigen::Vector2d, 2> uv_a, uv_b;
  double width_a, width_b;  // smaller side of each leaf's parameter rectangle
  double reach;             // sum of the leaves' radii [mm]
};

/// A leaf pair's contact before refinement.
struct PendingContact {
  LeafContact leaf{Contact{}, 0.0, 0.0, 0.0, 0.0};
  Eigen::Vector2d uv_b = Eigen::Vector2d::Zero();
  bool crossing = false;  // on a crossing (depth 0) or a near-touch (depth -gap)
  double reach = 0.0;
};

/// End points e and f (of different segments) coincide: within eps in space
/// and within half the smaller leaf on each surface in parameters.
bool ends_coincide(const Segment& s, int es, const Segment& t, int et, double eps) {
  const auto i = static_cast<std::size_t>(es), j = static_cast<std::size_t>(et);
  return (s.points[i] - t.points[j]).norm() <= eps &&
         (s.uv_a[i] - t.uv_a[j]).cwiseAbs().maxCoeff() <= 0.5 * std::min(s.width_a, t.width_a) &&
         (s.uv_b[i] - t.uv_b[j]).cwiseAbs().maxCoeff() <= 0.5 * std::min(s.width_b, t.width_b);
}

/// Chains segments into polylines: end points are matched greedily, closest
/// pairs first (ties by index, so the result is deterministic).
/// `reaches` gets, per curve point, the reach of the segment it came from.
std::vector<IntersectionCurve> chain_segments(const std::vector<Segment>& segments, double eps,
                                              std::vector<std::vector<double>>& reaches) {
  const int ends = static_cast<int>(2 * segments.size());
  const auto seg = [&](int e) -> const Segment& {
    return segments[static_cast<std::size_t>(e / 2)];
  };
  const auto pos = [&](int e) -> const Eigen::Vector3d& {
    return seg(e).points[static_cast<std::size_t>(e % 2)];
  };
  std::vector<int> by_x(static_cast<std::size_t>(ends));
  for (int e = 0; e < ends; ++e) by_x[static_cast<std::size_t>(e)] = e;
  std::sort(by_x.begin(), by_x.end(), [&](int a, int b) {
    return std::make_pair(pos(a).x(), a) < std::make_pair(pos(b).x(), b);
  });
  std::vector<std::tuple<double, int, int>> candidates;
  for (std::size_t x = 0; x < by_x.size(); ++x) {
    const int e = by_x[x];
    for (std::size_t y = x + 1; y < by_x.size(); ++y) {
      const int f = by_x[y];
      if (pos(f).x() - pos(e).x() > eps) break;
      if (e / 2 == f / 2) continue;
      if (ends_coincide(seg(e), e % 2, seg(f), f % 2, eps))
        candidates.emplace_back((pos(e) - pos(f)).norm(), std::min(e, f), std::max(e, f));
    }
  }
  std::sort(candidates.begin(), candidates.end());
  std::vector<int> next(static_cast<std::size_t>(ends), -1);  // matched end point
  for (const auto& [d, e, f] : candidates) {
    if (next[static_cast<std::size_t>(e)] >= 0 || next[static_cast<std::size_t>(f)] >= 0) continue;
    next[static_cast<std::size_t>(e)] = f;
    next[static_cast<std::size_t>(f)] = e;
  }
  std::vector<bool> used(segments.size(), false);
  std::vector<IntersectionCurve> curves;
  const auto append = [&](IntersectionCurve& c, int e) {
    const Segment& s = seg(e);
    const auto k = static_cast<std::size_t>(e % 2);
    reaches.back().push_back(s.reach);
    c.points.push_back(s.points[k]);
    c.uv_a.push_back(s.uv_a[k]);
    c.uv_b.push_back(s.uv_b[k]);
  };
  // Walks from end point `start` (its segment not yet used) until the chain
  // ends or closes.
  const auto walk = [&](int start) {
    IntersectionCurve c;
    reaches.emplace_back();
    append(c, start);
    int e = start;
    for (;;) {
      used[static_cast<std::size_t>(e / 2)] = true;
      const int far = e ^ 1;
      const int f = next[static_cast<std::size_t>(far)];
      if (f < 0 || used[static_cast<std::size_t>(f / 2)]) {
        // Closed when the far end meets the start point.
        append(c, f == start ? start : far);
        break;
      }
      append(c, far);
      e = f;
    }
    curves.push_back(std::move(c));
  };
  for (int e = 0; e < ends; ++e)  // open chains from their free ends
    if (!used[static_cast<std::size_t>(e / 2)] && next[static_cast<std::size_t>(e)] < 0) walk(e);
  for (int e = 0; e < ends; e += 2)  // what is left are closed loops
    if (!used[static_cast<std::size_t>(e / 2)]) walk(e);
  return curves;
}

/// Model size [mm] that refinement tolerances scale with.
double scale_of(const BSplineSurface& a, const BSplineSurface& b) {
  return std::max({control_point_box(a).diagonal(), control_point_box(b).diagonal(),
                   std::numeric_limits<double>::min()});
}

/// Refines one point pair; keeps the input when refinement leaves its leaves'
/// neighbourhood or does not converge (on_curve).
bool refine_in_place(const BSplineSurface& a, const BSplineSurface& b, Eigen::Vector3d& point,
                     Eigen::Vector2d& uv_a, Eigen::Vector2d& uv_b, bool on_curve, double reach,
                     double scale, double* gap = nullptr) {
  const RefinedPair r = refine_surface_pair(a, b, uv_a, uv_b, on_curve, scale);
  if (!((r.point - point).norm() <= reach)) return false;
  // Converged means on both surfaces up to rounding of the model size.
  if (on_curve && !(r.gap <= 1e-12 * scale)) return false;
  point = r.point;
  uv_a = r.uv_a;
  uv_b = r.uv_b;
  if (gap) *gap = r.gap;
  return true;
}

/// Inserts refined midpoints between consecutive refined curve points while
/// the curve strays more than `tolerance` from the chord: the leaf segments
/// are as long as the flat leaves, and the exact curve bends away from them
/// by up to its curvature times their length squared over 8.
void densify(const BSplineSurface& a, const BSplineSurface& b, IntersectionCurve& c,
             const std::vector<bool>& refined, double tolerance, double scale) {
  constexpr int kMaxDepth = 10;  // at most 2^10 pieces per leaf segment
  IntersectionCurve out;
  const auto push = [&out, &c](std::size_t k) {
    out.points.push_back(c.points[k]);
    out.uv_a.push_back(c.uv_a[k]);
    out.uv_b.push_back(c.uv_b[k]);
  };
  // Recursively fills the open interval between two refined points.
  struct Piece {
    Eigen::Vector3d p;
    Eigen::Vector2d ua, ub;
  };
  const auto fill = [&](auto&& self, const Piece& lo, const Piece& hi, int depth) -> void {
    if (depth >= kMaxDepth) return;
    Piece mid{0.5 * (lo.p + hi.p), 0.5 * (lo.ua + hi.ua), 0.5 * (lo.ub + hi.ub)};
    const Eigen::Vector3d chord_mid = mid.p;
    if (!refine_in_place(a, b, mid.p, mid.ua, mid.ub, true, (hi.p - lo.p).norm() + tolerance,
                         scale))
      return;
    if ((mid.p - chord_mid).norm() <= tolerance) return;
    self(self, lo, mid, depth + 1);
    out.points.push_back(mid.p);
    out.uv_a.push_back(mid.ua);
    out.uv_b.push_back(mid.ub);
    self(self, mid, hi, depth + 1);
  };
  for (std::size_t k = 0; k < c.points.size(); ++k) {
    push(k);
    if (k + 1 < c.points.size() && refined[k] && refined[k + 1])
      fill(fill, Piece{c.points[k], c.uv_a[k], c.uv_b[k]},
           Piece{c.points[k + 1], c.uv_a[k + 1], c.uv_b[k + 1]}, 0);
  }
  c = std::move(out);
}

}  // namespace

RefinedPair refine_surface_pair(const BSplineSurface& a, const BSplineSurface& b,
                                const Eigen::Vector2d& uv_a, const Eigen::Vector2d& uv_b,
                                bool on_curve, double scale) {
  Eigen::Vector4d x(uv_a[0], uv_a[1], uv_b[0], uv_b[1]);
  const Eigen::Vector4d lo(a.domain_start(Direction::u), a.domain_start(Direction::v),
                           b.domain_start(Direction::u), b.domain_start(Direction::v));
  const Eigen::Vector4d hi(a.domain_end(Direction::u), a.domain_end(Direction::v),
                           b.domain_end(Direction::u), b.domain_end(Direction::v));
  std::array<bool, 4> fixed{false, false, false, false};
  int fixed_count = 0;
  Eigen::Vector3d plane_normal = Eigen::Vector3d::Zero();
  Eigen::Vector3d plane_point = Eigen::Vector3d::Zero();
  if (on_curve) {
    for (int k = 0; k < 4; ++k) {
      if (x[k] == lo[k] || x[k] == hi[k]) {
        fixed[static_cast<std::size_t>(k)] = true;
        ++fixed_count;
      }
    }
    if (fixed_count == 0) {
      const SurfaceDerivatives da = evaluate_derivatives(a, x[0], x[1], 1);
      const SurfaceDerivatives db = evaluate_derivatives(b, x[2], x[3], 1);
      const Eigen::Vector3d t = unit_normal(da).cross(unit_normal(db));
      // Tangent surfaces have no curve direction: fall back to closest points.
      if (t.norm() > 1e-8) plane_normal = t.normalized();
      plane_point = 0.5 * (da.point + db.point);
    }
  }
  RefinedPair out;
  const double stop = 1e-14 * scale;
  constexpr int kMaxIterations = 40;
  double previous = std::numeric_limits<double>::infinity();
  for (int it = 0; it < kMaxIterations; ++it) {
    const SurfaceDerivatives da = evaluate_derivatives(a, x[0], x[1], 1);
    const SurfaceDerivatives db = evaluate_derivatives(b, x[2], x[3], 1);
    const Eigen::Vector3d f = da.point - db.point;
    out.iterations = it;
    const double residual = f.norm();
    if (residual <= stop) break;
    // Gauss-Newton stalls once rounding dominates: stop when |F| stops shrinking.
    if (it > 3 && residual >= 0.5 * previous) break;
    previous = residual;
    Eigen::Matrix<double, 5, 4> m = Eigen::Matrix<double, 5, 4>::Zero();
    Eigen::Matrix<double, 5, 1> rhs = Eigen::Matrix<double, 5, 1>::Zero();
    m.block<3, 1>(0, 0) = da.du;
    m.block<3, 1>(0, 1) = da.dv;
    m.block<3, 1>(0, 2) = -db.du;
    m.block<3, 1>(0, 3) = -db.dv;
    rhs.head<3>() = -f;
    int rows = 3;
    if (fixed_count > 0) {
      // Edge parameters stay put: their columns drop out of the step.
      for (int k = 0; k < 4; ++k)
        if (fixed[static_cast<std::size_t>(k)]) m.col(k).setZero();
    } else if (plane_normal.squaredNorm() > 0) {
      m(3, 0) = plane_normal.dot(da.du);
      m(3, 1) = plane_normal.dot(da.dv);
      rhs[3] = -plane_normal.dot(da.point - plane_point);
      rows = 4;
    }
    // Column scaling keeps the minimum-norm step meaningful when u and s
    // live on very different parameter ranges.
    Eigen::Vector4d col_scale;
    for (int k = 0; k < 4; ++k) {
      const double n = m.col(k).head(rows).norm();
      col_scale[k] = n > 0 ? 1.0 / n : 1.0;
    }
    const Eigen::MatrixXd ms = m.topRows(rows) * col_scale.asDiagonal();
    const Eigen::VectorXd step = col_scale.cwiseProduct(
        Eigen::Vector4d(ms.completeOrthogonalDecomposition().solve(rhs.head(rows))));
    const Eigen::Vector4d next = (x + step).cwiseMax(lo).cwiseMin(hi);
    if (next == x) break;
    x = next;
  }
  const Eigen::Vector3d pa = evaluate(a, x[0], x[1]);
  const Eigen::Vector3d pb = evaluate(b, x[2], x[3]);
  out.uv_a = x.head<2>();
  out.uv_b = x.tail<2>();
  out.point = 0.5 * (pa + pb);
  out.gap = (pa - pb).norm();
  return out;
}

CollisionResult collide(SurfaceHierarchy& ha, SurfaceHierarchy& hb,
                        const CollisionRequest& request) {
  CollisionResult result;
  // The tolerance must suit both surfaces.
  result.status = check_request(request, ha);
  if (result.status.ok()) result.status = check_request(request, hb);
  if (!result.status.ok()) return result;
  const double eps = request.tolerance;
  const double flat_tolerance = eps / 3.0;
  Side sa(ha, flat_tolerance, request.max_level, result.counters);
  Side sb(hb, flat_tolerance, request.max_level, result.counters);
  std::vector<Segment> segments;
  std::vector<PendingContact> pending;
  std::vector<std::pair<int, int>> stack{{sa.entry_of_block(0), sb.entry_of_block(0)}};
  std::vector<int> kids;
  while (!stack.empty()) {
    const auto [ea, eb] = stack.back();
    stack.pop_back();
    const View va = sa.view(ea);
    const View vb = sb.view(eb);
    // Everything of a pair lies in its spheres and boxes: farther apart than
    // eps, nothing in it can cross or touch within eps.
    if ((va.center - vb.center).norm() > va.radius + vb.radius + eps) continue;
    if (((va.lo - vb.hi).array() > eps).any() || ((vb.lo - va.hi).array() > eps).any()) continue;
    // A nearly flat side bounds by its triangles (worth it when flatness is
    // well below its radius).
    const bool thin_a = va.flatness < 0.5 * va.radius, thin_b = vb.flatness < 0.5 * vb.radius;
    if (thin_a && gap_to_flat_patch(va, vb) > eps) continue;
    if (thin_b && gap_to_flat_patch(vb, va) > eps) continue;
    if (thin_a && thin_b && triangles_farther_than(va, vb, eps)) continue;
    if (!(va.flat && vb.flat)) {
      // Split the side that is not flat; the larger sphere when neither is.
      const bool split_a = !va.flat && (vb.flat || va.radius >= vb.radius);
      if (split_a) {
        sa.children(ea, kids);
        for (auto it = kids.rbegin(); it != kids.rend(); ++it) stack.emplace_back(*it, eb);
      } else {
        sb.children(eb, kids);
        for (auto it = kids.rbegin(); it != kids.rend(); ++it) stack.emplace_back(ea, *it);
      }
      continue;
    }
    // Leaf pair: flat nodes are hierarchy nodes (blocks are never flat).
    ++result.counters.leaf_pairs;
    const LeafTriangles la = leaf_triangles(ha.node(ea));
    const LeafTriangles lb = leaf_triangles(hb.node(eb));
    const double width_a = std::min(la.u1 - la.u0, la.v1 - la.v0);
    const double width_b = std::min(lb.u1 - lb.u0, lb.v1 - lb.v0);
    const double reach = 2.0 * (la.radius + lb.radius) + eps;
    bool crossing = false;
    double longest = -1.0;
    PendingContact contact;
    double nearest = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < 2; ++i) {
      for (std::size_t j = 0; j < 2; ++j) {
        ++result.counters.triangle_tests;
        const TriangleIntersection x = intersect_triangles(la.triangles[i], lb.triangles[j]);
        if (x.kind != TriangleIntersection::Kind::none) {
          Segment s;
          s.points = x.points;
          for (std::size_t k = 0; k < 2; ++k) {
            s.uv_a[k] = param_of(la.params[i], x.bary_a[k]);
            s.uv_b[k] = param_of(lb.params[j], x.bary_b[k]);
          }
          s.width_a = width_a;
          s.width_b = width_b;
          s.reach = reach;
          const double length = (s.points[1] - s.points[0]).norm();
          if (length > longest) {
            longest = length;
            crossing = true;
            contact.leaf.contact.point = 0.5 * (s.points[0] + s.points[1]);
            contact.leaf.contact.uv_a = 0.5 * (s.uv_a[0] + s.uv_a[1]);
            contact.uv_b = 0.5 * (s.uv_b[0] + s.uv_b[1]);
            contact.leaf.contact.depth = 0.0;
          }
          // Point touches and coplanar overlaps are contacts, not curve pieces.
          if (x.kind == TriangleIntersection::Kind::segment && length > 0.0) segments.push_back(s);
        }
      }
    }
    // No crossing: the leaf pair is a contact when its triangles come within eps.
    for (std::size_t i = 0; i < 2 && !crossing && !request.first_crossing_only; ++i) {
      for (std::size_t j = 0; j < 2; ++j) {
        if (farther_than(la.triangles[i], lb.triangles[j], eps)) continue;
        const TriangleDistance d = triangle_distance(la.triangles[i], lb.triangles[j]);
        if (d.distance <= eps && d.distance < nearest) {
          nearest = d.distance;
          contact.leaf.contact.point = 0.5 * (d.point_a + d.point_b);
          contact.leaf.contact.uv_a = param_of(la.params[i], d.bary_a);
          contact.uv_b = param_of(lb.params[j], d.bary_b);
          contact.leaf.contact.depth = -d.distance;
        }
      }
    }
    if (!crossing && !std::isfinite(nearest)) continue;
    contact.crossing = crossing;
    contact.reach = reach;
    contact.leaf.u0 = la.u0;
    contact.leaf.u1 = la.u1;
    contact.leaf.v0 = la.v0;
    contact.leaf.v1 = la.v1;
    pending.push_back(contact);
    if (request.first_crossing_only) break;  // only crossings get here in that mode
  }

  const BSplineSurface& a = ha.surface();
  const BSplineSurface& b = hb.surface();
  const double scale = scale_of(a, b);
  std::vector<std::vector<double>> reaches;
  result.curves = chain_segments(segments, eps, reaches);
  if (request.refine) {
    for (std::size_t ci = 0; ci < result.curves.size(); ++ci) {
      IntersectionCurve& c = result.curves[ci];
      const std::size_t n = c.points.size();
      // A closed curve repeats its first point: refine it once.
      const bool closed = n > 2 && c.points[n - 1] == c.points[0] && c.uv_a[n - 1] == c.uv_a[0];
      std::vector<bool> refined(n, false);
      for (std::size_t k = 0; k < (closed ? n - 1 : n); ++k)
        refined[k] =
            refine_in_place(a, b, c.points[k], c.uv_a[k], c.uv_b[k], true, reaches[ci][k], scale);
      if (closed) {
        c.points[n - 1] = c.points[0];
        c.uv_a[n - 1] = c.uv_a[0];
        c.uv_b[n - 1] = c.uv_b[0];
        refined[n - 1] = refined[0];
      }
      densify(a, b, c, refined, eps / 3.0, scale);
    }
  }
  std::vector<LeafContact> leaves;
  leaves.reserve(pending.size());
  for (PendingContact& p : pending) {
    Contact& c = p.leaf.contact;
    if (request.refine) {
      if (p.crossing) {
        refine_in_place(a, b, c.point, c.uv_a, p.uv_b, true, p.reach, scale);
      } else {
        double gap = 0.0;
        const double before =
            (evaluate(a, c.uv_a[0], c.uv_a[1]) - evaluate(b, p.uv_b[0], p.uv_b[1])).norm();
        Eigen::Vector3d point = c.point;
        Eigen::Vector2d uv_a = c.uv_a, uv_b = p.uv_b;
        if (refine_in_place(a, b, point, uv_a, uv_b, false, p.reach, scale, &gap) &&
            gap <= before) {
          c.point = point;
          c.uv_a = uv_a;
          p.uv_b = uv_b;
          // Gauss-Newton stops at a crossing (gap ~ 0) or a local closest pair.
          c.depth = gap <= 1e-12 * scale ? 0.0 : -gap;
        }
      }
    }
    c.uv_b = p.uv_b;
    const SurfaceDerivatives d = evaluate_derivatives(a, c.uv_a[0], c.uv_a[1], 1);
    c.normal = unit_normal(d);
    if (c.normal.squaredNorm() == 0.0) c.normal = unit_normal(a, c.uv_a[0], c.uv_a[1]);
    c.tangent_u = d.du;
    c.tangent_v = d.dv;
    leaves.push_back(p.leaf);
  }
  if (!request.compute_depth || request.first_crossing_only) {
    group_regions(leaves, request.max_contacts, result);
    return result;
  }
  // Penetration needs each region's full extent, so trim only after adding it.
  group_regions(leaves, std::numeric_limits<int>::max(), result);
  add_penetration_contacts(a, b, result.contacts);
  rank_regions(result.contacts, result.region_count, request.max_contacts);
  return result;
}

}  // namespace argil
