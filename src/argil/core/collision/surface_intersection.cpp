#include "argil/core/collision/surface_intersection.hpp"

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <tuple>
#include <vector>

#include "argil/core/base/chunked_vector.hpp"
#include "argil/core/base/detail/id_slots.hpp"
#include "argil/core/collision/detail/contact_regions.hpp"
#include "argil/core/collision/detail/curve_densifier.hpp"
#include "argil/core/collision/detail/curve_end_march.hpp"
#include "argil/core/collision/detail/curve_tidy.hpp"
#include "argil/core/collision/detail/edge_crossings.hpp"
#include "argil/core/collision/detail/segment_chains.hpp"
#include "argil/core/collision/detail/surface_pair_refine.hpp"
#include "argil/core/collision/detail/swept_leaves.hpp"
#include "argil/core/collision/surface_contact.hpp"
#include "argil/core/collision/surface_penetration.hpp"
#include "argil/core/collision/triangle_intersection.hpp"
#include "argil/core/geometry/evaluate.hpp"
#include "argil/core/geometry/triangle_distance.hpp"
#include "argil/core/geometry/trim_region.hpp"
#include "argil/core/hierarchy/edge_crossings_bound.hpp"
#include "argil/core/hierarchy/normal_cone.hpp"

namespace argil {

namespace {

/// A triangle with what the cheap distance bounds read: its box, and its
/// plane's normal (not normalised) with that normal's length.
struct TriangleBound {
  Triangle t;
  Eigen::Vector3d lo, hi, normal;
  double length = 0.0;
};

TriangleBound bound_triangle(const Triangle& t) {
  TriangleBound b{t, t[0].cwiseMin(t[1]).cwiseMin(t[2]), t[0].cwiseMax(t[1]).cwiseMax(t[2]),
                  (t[1] - t[0]).cross(t[2] - t[0])};
  b.length = b.normal.norm();
  return b;
}

/// A node or a block of elements, copied out of its hierarchy (the node pool
/// may reallocate when children are created).
struct View {
  Eigen::Vector3d center;
  double radius;
  Eigen::Vector3d lo, hi;
  bool flat;
  /// Nodes only: flat, or flat to the coarse tolerance (PairDescent's
  /// transversal leaves; that tolerance is 0 when the query has none).
  bool coarse = false;
  /// Nodes only: the patch lies within `flatness` of its two corner
  /// triangles (c00, c10, c11), (c00, c11, c01); +inf for blocks.
  double flatness = std::numeric_limits<double>::infinity();
  std::array<Eigen::Vector3d, 4> corners{};
  /// A swept query's b: the node lies within `flatness` of its corner
  /// triangles moved by t `sweep`, for some t in [-1, 1] (half the motion's
  /// translation, kept apart from the flatness: a tool sliding along a
  /// surface moves along its triangles' planes). Zero otherwise.
  Eigen::Vector3d sweep = Eigen::Vector3d::Zero();
  /// The corner triangles' cheap bounds, placed: filled by corner_triangles()
  /// on first use (most views never need them).
  mutable std::optional<std::array<TriangleBound, 2>> triangles{};
};

/// A node view's two corner triangles with their cheap bounds, computed once.
const std::array<TriangleBound, 2>& corner_triangles(const View& v) {
  if (!v.triangles) {
    const auto& c = v.corners;
    v.triangles = {bound_triangle({c[0], c[1], c[3]}), bound_triangle({c[0], c[3], c[2]})};
  }
  return *v.triangles;
}

/// Whether a node is flat enough, for its size, that its corner triangles
/// bound it better than its sphere and box (false for blocks: flatness +inf).
bool is_thin(const View& v) { return v.flatness < 0.5 * v.radius; }

/// True when anything in `sphere` is more than eps from the patch of `node`
/// (a thin node): the sphere centre's distance to each corner triangle, less
/// the sphere radius and the node's flatness, exceeds eps. Far tighter than
/// the node's own sphere when the patch is nearly flat and wide (a plane
/// against a small tool), where sphere and box tests cannot separate what
/// lies near its plane. A triangle's plane is tried before the triangle
/// itself: its distance is a lower bound, and usually the same one.
bool sphere_apart_from_flat_patch(const View& node, const View& sphere, double eps) {
  // A swept node's triangles move by up to |sweep|, and off their planes by
  // the sweep's component along the normal only. (A swept sphere already
  // holds the whole motion.)
  const Eigen::Vector3d& h = node.sweep;
  for (const TriangleBound& t : corner_triangles(node)) {
    const Eigen::Vector3d to_centre = sphere.center - t.t[0];
    if (t.length > 0.0 &&
        (std::abs(t.normal.dot(to_centre)) - std::abs(t.normal.dot(h))) / t.length - sphere.radius -
                node.flatness >
            eps)
      continue;
    const Eigen::Vector3d foot = closest_point_on_triangle(sphere.center, t.t[0], t.t[1], t.t[2]);
    if (!((foot - sphere.center).norm() - h.norm() - sphere.radius - node.flatness > eps))
      return false;
  }
  return true;
}

/// The two corner triangles of a flat node and their parameter corners.
struct LeafTriangles {
  std::array<Triangle, 2> triangles;
  std::array<std::array<Eigen::Vector2d, 3>, 2> params;
  ParamRect rect;
  double radius;
};

LeafTriangles leaf_triangles(const HierarchyNode& n) {
  const auto& c = n.bound.corners;  // S(0,0), S(1,0), S(0,1), S(1,1)
  const Eigen::Vector2d p00 = n.rect.corner(0), p10 = n.rect.corner(1), p01 = n.rect.corner(2),
                        p11 = n.rect.corner(3);
  LeafTriangles t;
  // The same split as PatchBound::flatness: (c00, c10, c11), (c00, c11, c01).
  t.triangles = {Triangle{c[0], c[1], c[3]}, Triangle{c[0], c[3], c[2]}};
  t.params = {std::array<Eigen::Vector2d, 3>{p00, p10, p11},
              std::array<Eigen::Vector2d, 3>{p00, p11, p01}};
  t.rect = n.rect;
  t.radius = n.bound.radius;
  return t;
}

/// A rigid motion x -> R x + p that places one side's hierarchy in the
/// other's frame. Spheres, corner triangles and flatness move exactly; a box
/// becomes the box around the moved box (conservative).
struct Rigid {
  Eigen::Matrix3d R;
  Eigen::Vector3d p;

  Eigen::Vector3d operator()(const Eigen::Vector3d& x) const { return R * x + p; }
  void box(Eigen::Vector3d& lo, Eigen::Vector3d& hi) const {
    const Eigen::Vector3d centre = (*this)(0.5 * (lo + hi));
    const Eigen::Vector3d half = R.cwiseAbs() * (0.5 * (hi - lo));
    lo = centre - half;
    hi = centre + half;
  }
  Rigid inverse() const { return {R.transpose(), -(R.transpose() * p)}; }
};

/// b's motion in a swept query: its placement at the start and halfway (the
/// Side's own placement is the end); reach(), how far any point of b strays
/// from its halfway position on the way; `sagitta`, how far the corners'
/// arcs stray from the straight lines the leaf tests assume [mm].
struct Sweep {
  Rigid start;
  Rigid middle;
  /// The reach in two parts: half the translation, a point's straight line
  /// spanning t half_translation (t in [-1, 1]) about its midpoint, and the
  /// rest, from the turn (half its chord and the sagitta).
  Eigen::Vector3d half_translation = Eigen::Vector3d::Zero();
  double turn_reach = 0.0;
  double sagitta = 0.0;
  double travel = 0.0;  // the farthest any point of b moves [mm]

  double reach() const { return half_translation.norm() + turn_reach; }
};

/// What one side of a query remembers about the entries it has seen: ids map
/// to slots, slots index views and cones (so a query pays a slot per id, not
/// a view). Views never move (a chunked store: a doubling vector of them was
/// fresh memory, page faults, in every tick).
struct SideScratch {
  IdSlots node_slots, block_slots, cone_slots;
  ChunkedVector<View, 64> views;
  std::vector<std::optional<NormalCone>> cones;
  std::vector<double> leans;  // chord_lean along each cone's axis, NaN until asked

  /// Views kept for the next query: a haptic tick's queries see a few
  /// hundred (under 200 on the 64 x 64 panel); an offline query of two large
  /// faces can see millions, whose views (a few hundred bytes each) are
  /// freed rather than kept per thread.
  static constexpr std::size_t kKeptViews = 1 << 14;

  void clear() {
    node_slots.clear();
    block_slots.clear();
    cone_slots.clear();
    if (views.size() > kKeptViews) {
      views.truncate(0);
      node_slots.release();
      block_slots.release();
      cone_slots.release();
    } else {
      views.clear();
    }
    cones.clear();
    leans.clear();
  }
};

/// A side's scratch, taken from this thread's pool and given back cleared:
/// the next query reuses its memory instead of allocating, filling and
/// first-touching its own (a query holds two; a query inside a query more).
class SideScratchLease {
 public:
  SideScratchLease() {
    std::vector<std::unique_ptr<SideScratch>>& pool = free_pool();
    if (pool.empty()) {
      scratch_ = std::make_unique<SideScratch>();
    } else {
      scratch_ = std::move(pool.back());
      pool.pop_back();
    }
  }
  SideScratchLease(const SideScratchLease&) = delete;
  SideScratchLease& operator=(const SideScratchLease&) = delete;
  ~SideScratchLease() {
    scratch_->clear();
    free_pool().push_back(std::move(scratch_));
  }

  SideScratch* operator->() const { return scratch_.get(); }

 private:
  static std::vector<std::unique_ptr<SideScratch>>& free_pool() {
    thread_local std::vector<std::unique_ptr<SideScratch>> pool;
    return pool;
  }

  std::unique_ptr<SideScratch> scratch_;
};

/// Entries of one side: blocks as -(id + 1), hierarchy nodes as id >= 0.
class Side {
 public:
  Side(const SurfaceHierarchy& h, double flat_tolerance, double coarse_tolerance, int max_level,
       QueryCounters& counters, std::optional<Rigid> placed = std::nullopt,
       std::optional<Sweep> sweep = std::nullopt)
      : h_(h),
        flat_tolerance_(flat_tolerance),
        coarse_tolerance_(coarse_tolerance),
        max_level_(max_level),
        counters_(counters),
        placed_(std::move(placed)),
        sweep_(std::move(sweep)) {}

  /// The entry's bounds, placed (a reference that stays valid for the query).
  const View& view(int entry) {
    // An entry is read (and placed) once per query: the descent views each
    // node of one side against many of the other's.
    IdSlots& slots = entry < 0 ? scratch_->block_slots : scratch_->node_slots;
    const auto id = static_cast<std::size_t>(entry < 0 ? -entry - 1 : entry);
    int slot = slots.find(id);
    if (slot < 0) {
      slot = static_cast<int>(scratch_->views.size());
      slots.set(id, slot);
      scratch_->views.push_back(placed_ ? placed(own_view(entry)) : own_view(entry));
    }
    return scratch_->views[static_cast<std::size_t>(slot)];
  }

  /// A node's normal cone, placed (nullopt where normal_cone() gives none),
  /// computed once per query.
  const std::optional<NormalCone>& cone(int node) {
    const auto id = static_cast<std::size_t>(node);
    int slot = scratch_->cone_slots.find(id);
    if (slot < 0) {
      slot = static_cast<int>(scratch_->cones.size());
      scratch_->cone_slots.set(id, slot);
      std::optional<NormalCone> c = normal_cone(h_.node(node).patch);
      if (c && placed_) c->axis = placed_->R * c->axis;
      scratch_->cones.push_back(c);
      scratch_->leans.push_back(std::numeric_limits<double>::quiet_NaN());
    }
    return scratch_->cones[static_cast<std::size_t>(slot)];
  }

  /// chord_lean() of a node with a cone, along the cone's axis, computed
  /// once per query (call cone() first).
  double chord_lean(int node) {
    const int slot = scratch_->cone_slots.find(static_cast<std::size_t>(node));
    double& lean = scratch_->leans[static_cast<std::size_t>(slot)];
    if (std::isnan(lean)) {
      const NormalCone& c = *scratch_->cones[static_cast<std::size_t>(slot)];
      lean = argil::chord_lean(h_.node(node).patch, own_direction(c.axis));
    }
    return lean;
  }

  /// edge_rise() of a node's edge along a unit direction of the query's frame.
  double edge_rise(int node, PatchEdge edge, const Eigen::Vector3d& axis) const {
    return argil::edge_rise(h_.node(node).patch, edge, own_direction(axis));
  }

  /// A direction of the query's frame in the side's own.
  Eigen::Vector3d own_direction(const Eigen::Vector3d& d) const {
    return placed_ ? Eigen::Vector3d(placed_->R.transpose() * d) : d;
  }

  /// The entry's bounds in its own frame.
  View own_view(int entry) {
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
    return {b.center,   b.radius, b.box.min,
            b.box.max,  flat,     flat || b.flatness <= coarse_tolerance_,
            b.flatness, b.corners};
  }

  /// A leaf's corner triangles, placed.
  LeafTriangles leaf(int entry) const {
    LeafTriangles t = leaf_triangles(h_.node(entry));
    if (placed_)
      for (Triangle& triangle : t.triangles)
        for (Eigen::Vector3d& corner : triangle) corner = (*placed_)(corner);
    return t;
  }

  /// A leaf's corners in the side's own frame.
  detail::LeafCorners own_corners(int entry) const { return h_.node(entry).bound.corners; }

  /// A leaf's corners, placed (own corners when the side is not placed).
  detail::LeafCorners corners(int entry) const {
    detail::LeafCorners c = own_corners(entry);
    if (placed_)
      for (Eigen::Vector3d& x : c) x = (*placed_)(x);
    return c;
  }

  /// Entry of the block's single element, or the block itself.
  int entry_of_block(int block) {
    const ElementBlock& b = h_.block(block);
    return b.element_node >= 0 ? b.element_node : -(block + 1);
  }

  /// Up to four child entries (no allocation: the descent splits often).
  struct Children {
    std::array<int, 4> entries{};
    int count = 0;
  };

  Children children(int entry) {
    Children out;
    if (entry < 0) {
      const std::array<int, 4> kids = h_.block(-entry - 1).children;
      for (int c : kids)
        if (c >= 0) out.entries[static_cast<std::size_t>(out.count++)] = entry_of_block(c);
      return out;
    }
    for (int hu = 0; hu < 2; ++hu)
      for (int hv = 0; hv < 2; ++hv)
        out.entries[static_cast<std::size_t>(out.count++)] = h_.child(entry, hu, hv);
    return out;
  }

 private:
  View placed(const View& own) const {
    View v = placed_by(*placed_, own);
    if (!sweep_) return v;
    // Swept: everything on the way. Two bounds, both valid, the tighter kept:
    // the sphere and box around both ends (which contain the corners'
    // straight lines), and the halfway bounds grown by how far any point
    // strays from its halfway position. Only the second keeps corner
    // triangles, which separate a flat tool lying on a surface from it: the
    // flatness grows by the turn's part of the stray, and the translation's
    // part is kept as a vector (View::sweep), so a tool sliding along a
    // surface stays as far from it as it is at rest.
    const View start = placed_by(sweep_->start, own);
    View middle = placed_by(sweep_->middle, own);
    const double grow = sweep_->reach();
    const double travel = (v.center - start.center).norm();
    if (own.radius + 0.5 * travel < middle.radius + grow) {
      middle.center = 0.5 * (v.center + start.center);
      middle.radius = own.radius + 0.5 * travel;
    } else {
      middle.radius += grow;
    }
    middle.lo = (middle.lo.array() - grow).max(v.lo.cwiseMin(start.lo).array());
    middle.hi = (middle.hi.array() + grow).min(v.hi.cwiseMax(start.hi).array());
    middle.flatness += sweep_->turn_reach;  // +inf stays +inf
    middle.sweep = sweep_->half_translation;
    return middle;
  }

  static View placed_by(const Rigid& motion, View v) {
    v.center = motion(v.center);
    motion.box(v.lo, v.hi);
    for (Eigen::Vector3d& c : v.corners) c = motion(c);
    return v;
  }

  const SurfaceHierarchy& h_;
  double flat_tolerance_;
  double coarse_tolerance_;  // 0: no coarse leaves
  int max_level_;
  QueryCounters& counters_;
  std::optional<Rigid> placed_;
  std::optional<Sweep> sweep_;  // a swept query's motion
  SideScratchLease scratch_;
};

/// True when every point of `other` lies more than eps beyond the plane
/// through `origin` with normal n (length |n|), on either side.
bool beyond_plane(const Eigen::Vector3d& n, double length, const Eigen::Vector3d& origin,
                  const Triangle& other, double eps) {
  if (!(length > 0.0)) return false;
  const double limit = eps * length;
  const double d0 = n.dot(other[0] - origin);
  const double d1 = n.dot(other[1] - origin);
  const double d2 = n.dot(other[2] - origin);
  return std::min({d0, d1, d2}) > limit || std::max({d0, d1, d2}) < -limit;
}

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
  const auto beyond = [eps](const Triangle& t, const Triangle& other) {
    const Eigen::Vector3d n = (t[1] - t[0]).cross(t[2] - t[0]);
    return beyond_plane(n, n.norm(), t[0], other, eps);
  };
  return beyond(a, b) || beyond(b, a);
}

/// The same test from bounds computed once per node (the descent tests each
/// node's triangles against many of the other side's): the same arithmetic.
bool farther_than(const TriangleBound& a, const TriangleBound& b, double eps) {
  if (((b.lo - a.hi).cwiseMax(a.lo - b.hi).array() > eps).any()) return true;
  return beyond_plane(a.normal, a.length, a.t[0], b.t, eps) ||
         beyond_plane(b.normal, b.length, b.t[0], a.t, eps);
}

/// The same for b moved by t h against a, for every t in [-1, 1]: the boxes
/// grow by |h| per axis, and each plane test by h's part along its normal.
bool farther_than(const TriangleBound& a, const TriangleBound& b, double eps,
                  const Eigen::Vector3d& h) {
  if ((((b.lo - a.hi).cwiseMax(a.lo - b.hi) - h.cwiseAbs()).array() > eps).any()) return true;
  const auto along = [&h](const TriangleBound& t) {
    return t.length > 0.0 ? std::abs(t.normal.dot(h)) / t.length : 0.0;
  };
  return beyond_plane(a.normal, a.length, a.t[0], b.t, eps + along(a)) ||
         beyond_plane(b.normal, b.length, b.t[0], a.t, eps + along(b));
}

/// True when every corner triangle of node a is more than eps + both
/// flatness bounds from every corner triangle of node b (cheap tests only),
/// so the patches are more than eps apart. Separates tilted thin patches
/// that sphere and axis-aligned box tests cannot. Both nodes thin.
bool triangles_farther_than(const View& a, const View& b, double eps) {
  const double margin = eps + a.flatness + b.flatness;
  const Eigen::Vector3d& h = b.sweep;  // only b moves in a swept query
  const bool swept = !h.isZero(0.0);
  for (const TriangleBound& x : corner_triangles(a))
    for (const TriangleBound& y : corner_triangles(b))
      if (swept ? !farther_than(x, y, margin, h) : !farther_than(x, y, margin)) return false;
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
      const SurfaceDerivatives d = evaluate_derivatives(a, deepest.uv_a[0], deepest.uv_a[1], 1);
      Contact c = contact_at(a, deepest.uv_a, d, deepest.depth);
      c.uv_b = deepest.uv_b;
      c.region = contacts[begin].region;
      contacts.push_back(c);  // may reallocate: `region` is not used after this
    }
    begin = end;
  }
}

Eigen::Vector2d param_of(const std::array<Eigen::Vector2d, 3>& p, const Eigen::Vector3d& w) {
  return w[0] * p[0] + w[1] * p[1] + w[2] * p[2];
}

/// A leaf pair's contact before refinement (b's parameters in contact.uv_b).
struct PendingContact {
  LeafContact leaf{};
  bool crossing = false;  // on a crossing (depth 0) or a near-touch (depth -gap)
  bool refined = false;   // already on both exact surfaces (a transversal leaf's)
  double reach = 0.0;
};

/// A descent's contacts before refinement: the leaf contacts, and beside them
/// what refinement reads. Kept apart so that the leaf contacts are finished
/// and grouped where they lie: a tool lying on a face finds thousands, and a
/// copy of them was fresh memory (page faults) in every haptic tick.
struct PendingContacts {
  struct Origin {
    bool crossing = false;
    bool refined = false;
    double reach = 0.0;
  };
  std::vector<LeafContact> leaves;
  std::vector<Origin> origins;

  void add(const PendingContact& c) {
    leaves.push_back(c.leaf);
    origins.push_back({c.crossing, c.refined, c.reach});
  }
  void append(const PendingContacts& other) {
    leaves.insert(leaves.end(), other.leaves.begin(), other.leaves.end());
    origins.insert(origins.end(), other.origins.begin(), other.origins.end());
  }
};

/// The contacts whose uv_a `material` does not contain, moved out of
/// `pending` (in their order). Nothing moves for a null or empty material.
std::vector<LeafContact> take_off_material(PendingContacts& pending, const TrimRegion* material) {
  std::vector<LeafContact> off;
  if (!material || material->empty()) return off;
  std::size_t kept = 0;
  for (std::size_t i = 0; i < pending.leaves.size(); ++i) {
    if (!material->contains(pending.leaves[i].contact.uv_a)) {
      off.push_back(pending.leaves[i]);
      continue;
    }
    pending.leaves[kept] = pending.leaves[i];
    pending.origins[kept] = pending.origins[i];
    ++kept;
  }
  pending.leaves.resize(kept);
  pending.origins.resize(kept);
  return off;
}

double scale_of(const BSplineSurface& a, const BSplineSurface& b) {
  return std::max({control_point_box(a).diagonal(), control_point_box(b).diagonal(),
                   std::numeric_limits<double>::min()});
}

/// Curve point k replaced by its refinement, with the curve's tangent there;
/// nullopt when refinement failed.
std::optional<CurveTangent> refine_curve_point(const SurfacePair& pair, IntersectionCurve& c,
                                               std::size_t k, double reach) {
  const std::optional<RefinedPair> r =
      refine_near(pair, {c.points[k], c.uv_a[k], c.uv_b[k]}, true, reach);
  if (!r) return std::nullopt;
  c.points[k] = r->point;
  c.uv_a[k] = r->uv_a;
  c.uv_b[k] = r->uv_b;
  return r->tangent;
}

/// Leaves out each refined point of a transversal leaf from which the curve
/// steps back along the way it came (a turn of more than 154 degrees between
/// refined neighbours, the step no longer than the point's reach). Such a
/// leaf's points start off the curve by up to its flatness over the crossing
/// angle's sine, and refinement moves them across the curve: a crossing of
/// its triangles' diagonal next to the leaf's edge can land behind the edge's
/// point, and near a leaf's corner two neighbours' ends, held on different
/// edges, can land in the other order. The densifier then follows the curve
/// between the points kept.
void drop_steps_back(IntersectionCurve& c, std::vector<bool>& refined,
                     std::vector<std::optional<CurveTangent>>& tangents,
                     const std::vector<bool>& pinned, const std::vector<double>& reaches) {
  if (c.points.empty()) return;
  constexpr double kBackCosine = -0.9;
  std::size_t kept = 1, last = 0;
  for (std::size_t k = 1; k < c.points.size(); ++k) {
    bool back = false;
    if (k + 1 < c.points.size() && pinned[k] && refined[last] && refined[k] && refined[k + 1]) {
      const Eigen::Vector3d in = c.points[k] - c.points[last];
      const Eigen::Vector3d out = c.points[k + 1] - c.points[k];
      const double lengths = in.norm() * out.norm();
      back = lengths > 0.0 && in.dot(out) < kBackCosine * lengths &&
             std::min(in.norm(), out.norm()) <= reaches[k];
    }
    if (back) continue;
    c.points[kept] = c.points[k];
    c.uv_a[kept] = c.uv_a[k];
    c.uv_b[kept] = c.uv_b[k];
    refined[kept] = refined[k];
    tangents[kept] = tangents[k];
    last = kept++;
  }
  c.points.resize(kept);
  c.uv_a.resize(kept);
  c.uv_b.resize(kept);
  refined.resize(kept);
  tangents.resize(kept);
}

/// Refines every point of the curve not yet refined (a closed curve's
/// repeated end once), leaves out steps back, then densifies between refined
/// neighbours.
IntersectionCurve refine_curve(const SurfacePair& pair, IntersectionCurve c,
                               const std::vector<double>& reaches, const std::vector<bool>& pinned,
                               const std::vector<CurveTangent>& pinned_tangents, double eps) {
  const std::size_t n = c.points.size();
  // A closed curve repeats its first point: refine it once.
  const bool closed = n > 2 && c.points[n - 1] == c.points[0] && c.uv_a[n - 1] == c.uv_a[0];
  std::vector<bool> refined(n, false);
  std::vector<std::optional<CurveTangent>> tangents(n);
  // A transversal leaf's points were refined in the descent (pinned), with
  // their tangents; the densifier starts from those (the leaves' segments
  // are long).
  for (std::size_t k = 0; k < (closed ? n - 1 : n); ++k) {
    tangents[k] = pinned[k] ? pinned_tangents[k] : refine_curve_point(pair, c, k, reaches[k]);
    refined[k] = pinned[k] || tangents[k].has_value();
  }
  if (closed) {
    c.points[n - 1] = c.points[0];
    c.uv_a[n - 1] = c.uv_a[0];
    c.uv_b[n - 1] = c.uv_b[0];
    refined[n - 1] = refined[0];
    tangents[n - 1] = tangents[0];
  }
  drop_steps_back(c, refined, tangents, pinned, reaches);
  return CurveDensifier(pair, eps / 3.0).run(c, refined, tangents);
}

/// Refined pieces of one curve can end up to about 1.6 eps apart (where
/// leaves of different sizes meet), or a leaf's edge apart along a knot line
/// of both surfaces: the bridge fills such a gap with refined points when one
/// branch runs across it.
detail::GapBridge bridge_for(const SurfacePair& pair, double eps) {
  return [&pair, eps](const detail::CurvePoint& from, const detail::CurvePoint& to) {
    return CurveDensifier(pair, eps / 3.0)
        .between({from.point, from.uv_a, from.uv_b}, {to.point, to.uv_a, to.uv_b});
  };
}

/// Pieces of a curve along an edge two faces share can stop short of the
/// edge's end, where no triangle pair found the curve: the march follows it on.
detail::EndMarch march_for(const SurfacePair& pair, double eps) {
  return [&pair, eps](const detail::CurvePoint& end, const Eigen::Vector3d& outward,
                      const ChordStop& stop) {
    return march_from_end(pair, {end.point, end.uv_a, end.uv_b}, outward, eps / 3.0, stop);
  };
}

/// Moves a near-touch contact to a local closest pair when that is no farther
/// apart than the start: depth -gap, or 0 where the surfaces turn out to cross.
void refine_near_touch(const SurfacePair& pair, Contact& c, double reach) {
  const double before = (pair.eval_a.evaluate(c.uv_a[0], c.uv_a[1], 0).point -
                         pair.eval_b.evaluate(c.uv_b[0], c.uv_b[1], 0).point)
                            .norm();
  const std::optional<RefinedPair> r = refine_near(pair, {c.point, c.uv_a, c.uv_b}, false, reach);
  if (!r || !(r->gap <= before)) return;
  c.point = r->point;
  c.uv_a = r->uv_a;
  c.uv_b = r->uv_b;
  // Gauss-Newton stops at a crossing (gap ~ 0) or a local closest pair.
  c.depth = r->gap <= 1e-12 * pair.scale ? 0.0 : -r->gap;
}

/// Refines a pending contact onto the exact surfaces: its point, parameters
/// and depth, what regions are grouped and ranked by (a's normal and
/// tangents are left to with_frame, for the contacts kept).
void refine_contact(const SurfacePair& pair, Contact& c, const PendingContacts::Origin& origin) {
  if (origin.refined) return;
  if (!origin.crossing) {
    refine_near_touch(pair, c, origin.reach);
    return;
  }
  if (const std::optional<RefinedPair> r =
          refine_near(pair, {c.point, c.uv_a, c.uv_b}, true, origin.reach)) {
    c.point = r->point;
    c.uv_a = r->uv_a;
    c.uv_b = r->uv_b;
  }
}

/// The contact with a's normal and tangents at its parameters (its point,
/// between the two surfaces, stays). Only the contacts a query returns get
/// them: a tool lying on a face finds thousands of leaf pairs and keeps 64.
Contact with_frame(const BSplineSurface& a, const Contact& c) {
  const SurfaceDerivatives d = evaluate_derivatives(a, c.uv_a[0], c.uv_a[1], 1);
  Contact framed = contact_at(a, c.uv_a, d, c.depth);
  framed.point = c.point;
  framed.uv_b = c.uv_b;
  framed.region = c.region;
  return framed;
}

/// True when node pair (va, vb) is certainly more than eps apart: spheres,
/// boxes, and for nearly flat sides their corner triangles.
bool pair_apart(const View& va, const View& vb, double eps) {
  // Everything of a pair lies in its spheres and boxes.
  if ((va.center - vb.center).norm() > va.radius + vb.radius + eps) return true;
  if (((va.lo - vb.hi).array() > eps).any() || ((vb.lo - va.hi).array() > eps).any()) return true;
  // A nearly flat side bounds by its triangles (worth it when flatness is
  // well below its radius). Each test is conservative on its own, so which
  // run is only cost: two thin sides compare their triangles' cheap bounds
  // (the sphere tests after a failed one pruned 6% of what they examined,
  // and cost more than splitting those pairs), one thin side measures the
  // other's sphere against its triangles.
  const bool thin_a = is_thin(va), thin_b = is_thin(vb);
  if (thin_a && thin_b) return triangles_farther_than(va, vb, eps);
  if (thin_a && sphere_apart_from_flat_patch(va, vb, eps)) return true;
  return thin_b && sphere_apart_from_flat_patch(vb, va, eps);
}

/// What one flat leaf pair gives: crossing segments and at most one contact.
struct LeafPairFindings {
  std::vector<detail::Segment> segments;
  std::optional<PendingContact> contact;
  long triangle_tests = 0;
};

/// How far from a triangle's plane a corner still counts as on it, for a whole
/// query (so a corner two leaves share is decided alike in both): the
/// rounding of surface evaluation (64 ulps of the largest coordinate either
/// surface reaches, b placed), and never more than a millionth of eps. Without
/// it a face boundary lying in its neighbour's plane falls on either side by
/// rounding, and the curve along the shared edge breaks wherever it falls outside.
double on_plane_distance(const BSplineSurface& a, const BSplineSurface& b,
                         const std::optional<Rigid>& placed_b, double eps) {
  double magnitude = a.control_points.cwiseAbs().maxCoeff();
  if (placed_b) {
    // |R x + p| <= |x| + |p| for a rotation R.
    magnitude =
        std::max(magnitude, b.control_points.rowwise().norm().maxCoeff() + placed_b->p.norm());
  } else {
    magnitude = std::max(magnitude, b.control_points.cwiseAbs().maxCoeff());
  }
  constexpr double kRoundingUlps = 64.0;
  return std::min(1e-6 * eps, kRoundingUlps * std::numeric_limits<double>::epsilon() * magnitude);
}

/// Whether two crossing triangles lie where their surfaces coincide to within
/// eps (faces lying on each other: a face against itself, or coincident faces
/// of an assembly). Their leaves' triangles then cross wherever rounding or
/// the surfaces' small turn over a leaf puts them, along leaf edges and
/// across leaves, and such a crossing is no curve piece: the leaf pair's
/// contact reports the overlap instead.
class CoincidenceTest {
 public:
  /// b's normals turn by R_AB when b is placed in a's frame.
  CoincidenceTest(const BSplineSurface& a, const BSplineSurface& b, const Eigen::Matrix3d& R_AB,
                  double eps)
      : a_(a), b_(b), R_AB_(R_AB), eps_(eps) {}

  /// True when two crossing triangles meet at an angle past any turn of a
  /// flat leaf: their surfaces cross there, whatever the exact normals say.
  bool steep(const Triangle& ta, const Triangle& tb) const {
    const Eigen::Vector3d ta_n = (ta[1] - ta[0]).cross(ta[2] - ta[0]);
    const Eigen::Vector3d tb_n = (tb[1] - tb[0]).cross(tb[2] - tb[0]);
    return ta_n.cross(tb_n).norm() > kSteep * ta_n.norm() * tb_n.norm();
  }

  /// True when the surfaces' exact normals at the segment's middle are so
  /// nearly parallel that across the larger leaf (`diameter` [mm]) their
  /// tangent planes part by at most eps: the surfaces are tangent there. (Each
  /// also bends from its tangent plane across a leaf, a few eps at most for a
  /// flat leaf; surfaces that touch with different curvature come out as
  /// contacts too, as a touch should.)
  bool tangent_at(const detail::Segment& s, double diameter) const {
    const Eigen::Vector2d uv_a = 0.5 * (s.uv_a[0] + s.uv_a[1]);
    const Eigen::Vector2d uv_b = 0.5 * (s.uv_b[0] + s.uv_b[1]);
    const Eigen::Vector3d na = unit_normal(a_, uv_a[0], uv_a[1]);
    const Eigen::Vector3d nb = R_AB_ * unit_normal(b_, uv_b[0], uv_b[1]);
    // No normal at a pole or a collapsed corner: not known to coincide.
    if (na.isZero() || nb.isZero()) return false;
    return na.cross(nb).norm() * diameter <= eps_;
  }

 private:
  /// A flat leaf's triangles turn from its surface by about the surface's turn
  /// over the leaf, small at any eps a user asks for: past this sine of the
  /// triangles' angle, the surfaces cross at an angle.
  static constexpr double kSteep = 0.7;
  const BSplineSurface& a_;
  const BSplineSurface& b_;
  Eigen::Matrix3d R_AB_;
  double eps_;
};

/// Intersects the leaves' four triangle pairs; the contact sits on the
/// longest crossing segment's midpoint (depth 0). A crossing where the
/// surfaces coincide (`coincide`, given only when curves are asked for) is a
/// contact, not a curve piece.
LeafPairFindings leaf_crossings(const LeafTriangles& la, const LeafTriangles& lb, double reach,
                                double on_plane, const CoincidenceTest* coincide) {
  LeafPairFindings out;
  double longest = -1.0;
  // The exact normals' answer, read at the first gentle segment and kept for
  // the leaf pair's others: within a flat leaf it changes only for a crossing
  // right at the threshold, which then goes one way for the whole pair.
  std::optional<bool> tangent;
  for (std::size_t i = 0; i < 2; ++i) {
    for (std::size_t j = 0; j < 2; ++j) {
      ++out.triangle_tests;
      const TriangleIntersection x =
          intersect_triangles(la.triangles[i], lb.triangles[j], on_plane);
      if (x.kind == TriangleIntersection::Kind::none) continue;
      detail::Segment s{x.points, {}, {}, la.rect.min_side(), lb.rect.min_side(), reach};
      for (std::size_t k = 0; k < 2; ++k) {
        s.uv_a[k] = param_of(la.params[i], x.bary_a[k]);
        s.uv_b[k] = param_of(lb.params[j], x.bary_b[k]);
      }
      const double length = (s.points[1] - s.points[0]).norm();
      if (length > longest) {
        longest = length;
        PendingContact c;
        c.leaf.contact.point = 0.5 * (s.points[0] + s.points[1]);
        c.leaf.contact.uv_a = 0.5 * (s.uv_a[0] + s.uv_a[1]);
        c.leaf.contact.uv_b = 0.5 * (s.uv_b[0] + s.uv_b[1]);
        c.crossing = true;
        out.contact = c;
      }
      // Point touches and coplanar overlaps are contacts, not curve pieces.
      if (x.kind != TriangleIntersection::Kind::segment || !(length > 0.0)) continue;
      if (coincide && !coincide->steep(la.triangles[i], lb.triangles[j])) {
        if (!tangent) tangent = coincide->tangent_at(s, 2.0 * std::max(la.radius, lb.radius));
        if (*tangent) continue;
      }
      out.segments.push_back(s);
    }
  }
  return out;
}

/// Without a crossing, the leaf pair is a contact when its triangles come
/// within eps: halfway between the closest triangle points, depth -distance.
std::optional<PendingContact> leaf_near_touch(const LeafTriangles& la, const LeafTriangles& lb,
                                              double eps) {
  std::optional<PendingContact> out;
  double nearest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < 2; ++i) {
    for (std::size_t j = 0; j < 2; ++j) {
      // No nearer than the nearest pair so far: no need to measure it.
      if (farther_than(la.triangles[i], lb.triangles[j], std::min(eps, nearest))) continue;
      const TriangleDistance d = triangle_distance(la.triangles[i], lb.triangles[j]);
      if (!(d.distance <= eps && d.distance < nearest)) continue;
      nearest = d.distance;
      PendingContact c;
      c.leaf.contact.point = 0.5 * (d.point_a + d.point_b);
      c.leaf.contact.uv_a = param_of(la.params[i], d.bary_a);
      c.leaf.contact.uv_b = param_of(lb.params[j], d.bary_b);
      c.leaf.contact.depth = -d.distance;
      out = c;
    }
  }
  return out;
}

/// True when every triangle of one leaf is more than `distance` from every
/// triangle of the other (cheap bounds only).
bool leaves_farther_than(const LeafTriangles& la, const LeafTriangles& lb, double distance) {
  for (const Triangle& x : la.triangles)
    for (const Triangle& y : lb.triangles)
      if (!farther_than(x, y, distance)) return false;
  return true;
}

/// True when an arc of the exact intersection could end on edge `k` of leaf
/// `edges_of` (ring order c00-c10, c10-c11, c11-c01, c01-c00, as PatchEdge):
/// the straight edge comes within `band` of the other leaf's triangles
/// (touching them counts: a corner on the other's triangles gives no
/// crossing segment). Each straight edge lies within its leaf's flatness of
/// the patch's edge at the same parameter, and the other patch within its
/// own flatness of its triangles, so an arc ending on an edge puts the
/// straight edge within the two flatnesses of the triangles (`band`: those
/// plus rounding).
bool edge_may_hide_crossing(const LeafTriangles& edges_of, std::size_t k,
                            const LeafTriangles& other, double band) {
  const Triangle& t0 = edges_of.triangles[0];
  const Triangle& t1 = edges_of.triangles[1];
  const std::array<Eigen::Vector3d, 4> ring{t0[0], t0[1], t0[2], t1[2]};  // c00, c10, c11, c01
  const Eigen::Vector3d& p0 = ring[k];
  const Eigen::Vector3d& p1 = ring[(k + 1) % 4];
  const Eigen::Vector3d lo = p0.cwiseMin(p1).array() - band, hi = p0.cwiseMax(p1).array() + band;
  for (const Triangle& t : other.triangles) {
    // The triangle outside the edge's box grown by band: farther than band.
    if ((t[0].cwiseMax(t[1]).cwiseMax(t[2]).array() < lo.array()).any() ||
        (t[0].cwiseMin(t[1]).cwiseMin(t[2]).array() > hi.array()).any())
      continue;
    // Both ends farther than band on one side of the plane: farther from the triangle.
    const Eigen::Vector3d n = (t[1] - t[0]).cross(t[2] - t[0]);
    const double length = n.norm();
    if (length > 0.0) {
      const double s0 = n.dot(p0 - t[0]) / length, s1 = n.dot(p1 - t[0]) / length;
      if ((s0 > band && s1 > band) || (s0 < -band && s1 < -band)) continue;
    }
    if (segment_triangle_distance(p0, p1, t[0], t[1], t[2]) <= band) return true;
  }
  return false;
}

/// True when (u, v) lies in the rectangle grown by 1e-9 of its sides (rounding).
bool inside(const ParamRect& r, const Eigen::Vector2d& uv) {
  const double du = 1e-9 * r.width(), dv = 1e-9 * r.height();
  return uv[0] >= r.u0 - du && uv[0] <= r.u1 + du && uv[1] >= r.v0 - dv && uv[1] <= r.v1 + dv;
}

/// The simultaneous descent of collide(a, b) over node pairs (see the header).
/// A swept query runs it at the end placement first; only when nothing
/// crosses there is the way looked at: a pair that met on it ends no farther
/// apart than b moved, so for a motion within eps the end's descent has
/// already reached every such pair (it keeps them), and a longer one needs a
/// descent of its own with bounds over the whole motion.
class PairDescent {
 public:
  enum class Pass {
    end,  // the placement at the end (the only one of an unswept query)
    way,  // a swept query's motion: stops at the first leaf pair that meets on it
  };

  /// `exact`: both exact surfaces (b placed), onto which transversal leaves
  /// refine their crossings; coarse_tolerance() decides whether the query
  /// has any.
  PairDescent(const SurfaceHierarchy& ha, const SurfaceHierarchy& hb,
              const std::optional<Rigid>& placed_b, const std::optional<Sweep>& sweep, Pass pass,
              const CollisionRequest& request, QueryCounters& counters,
              const SurfacePair* exact = nullptr)
      : request_(request),
        counters_(counters),
        exact_(exact),
        coarse_(exact ? coarse_tolerance(ha, hb, sweep, request) : 0.0),
        sa_(ha, request.tolerance / 3.0, coarse_ / 3.0, request.max_level, counters),
        sb_(hb, request.tolerance / 3.0, coarse_ / 3.0, request.max_level, counters, placed_b,
            pass == Pass::way ? sweep : std::nullopt),
        on_plane_(on_plane_distance(ha.surface(), hb.surface(), placed_b, request.tolerance)),
        apart_(request.tolerance + (pass == Pass::way ? sweep->sagitta : 0.0)),
        way_(pass == Pass::way) {
    if (sweep) {
      motion_ =
          SweptMotion{sweep->start, sweep->start.inverse(), placed_b->inverse(), sweep->travel};
      keep_near_ = pass == Pass::end && sweep->travel <= request.tolerance;
    }
    if (request.curves && pass == Pass::end)
      coincide_.emplace(ha.surface(), hb.surface(),
                        placed_b ? placed_b->R : Eigen::Matrix3d::Identity(), request.tolerance);
    if (coarse_ > 0.0) edge_crossings_.emplace(*exact_);
  }

  void run() {
    std::vector<std::pair<int, int>> stack{{sa_.entry_of_block(0), sb_.entry_of_block(0)}};
    while (!stack.empty()) {
      const auto [ea, eb] = stack.back();
      stack.pop_back();
      const View& va = sa_.view(ea);
      const View& vb = sb_.view(eb);
      if (pair_apart(va, vb, apart_)) continue;
      if (!(va.flat && vb.flat)) {
        // A transversal pair is a leaf when its crossings refine (see
        // coarse_leaf_pair); it is split like any other otherwise.
        if (transversal(ea, va, eb, vb) && coarse_leaf_pair(ea, va, eb, vb)) continue;
        // Split the side that is not flat; the larger sphere when neither is.
        const bool split_a = !va.flat && (vb.flat || va.radius >= vb.radius);
        const Side::Children kids = split_a ? sa_.children(ea) : sb_.children(eb);
        for (int k = kids.count - 1; k >= 0; --k) {
          const int kid = kids.entries[static_cast<std::size_t>(k)];
          stack.emplace_back(split_a ? kid : ea, split_a ? eb : kid);
        }
        continue;
      }
      // Leaf pair: flat nodes are hierarchy nodes (blocks are never flat).
      ++counters_.leaf_pairs;
      if (way_ ? way_leaf_pair(ea, eb) : examine_leaf_pair(ea, eb)) {
        if (way_ || request_.first_crossing_only || (request_.stop_at_crossing && crossed_)) break;
      }
    }
  }

  /// A leaf pair crossed at the placement.
  bool crossed() const { return crossed_; }

  /// Whether the end's descent reached every leaf pair that could have met on
  /// the way (a motion within eps), and kept them for meet_kept_pairs_on_the_way.
  bool kept_the_way() const { return keep_near_; }

  /// The end's descent: the first pair it kept that meets on the way gives a
  /// crossing.
  void meet_kept_pairs_on_the_way() {
    for (const auto& [ea, eb] : near_)
      if (meets_on_the_way(ea, eb, sa_.leaf(ea), sb_.leaf(eb))) return;
  }

  std::vector<detail::Segment> segments;
  PendingContacts pending;

 private:
  /// The tolerance coarse leaves are flat to, 0 for none: only refined
  /// curves of one placement (no sweep) get them, as refinement moves their
  /// points onto the exact curve and the densifier follows it between them.
  static double coarse_tolerance(const SurfaceHierarchy& ha, const SurfaceHierarchy& hb,
                                 const std::optional<Sweep>& sweep,
                                 const CollisionRequest& request) {
    if (!request.refine || !request.curves || request.first_crossing_only ||
        request.stop_at_crossing || sweep)
      return 0.0;
    return std::max(request.tolerance, kCoarseFraction * scale_of(ha.surface(), hb.surface()));
  }

  /// True when both nodes are flat to the coarse tolerance and their normals
  /// meet at kTransversalAngle or more everywhere: the surfaces cross there
  /// at an angle, in arcs that run to the pair's edges (no closed loop, no
  /// tangency), which the coarse triangles follow within their flatness over
  /// the angle's sine, and which refinement and the densifier then trace on
  /// the exact surfaces. Such a pair is a leaf however far from eps-flat.
  bool transversal(int ea, const View& va, int eb, const View& vb) {
    if (!(coarse_ > 0.0) || !(va.coarse && vb.coarse) || ea < 0 || eb < 0) return false;
    const std::optional<NormalCone>& ca = sa_.cone(ea);
    if (!ca) return false;
    const std::optional<NormalCone>& cb = sb_.cone(eb);
    return cb && least_crossing_angle(*ca, *cb) >= kTransversalAngle;
  }

  /// True when the pair gave a contact.
  bool examine_leaf_pair(int ea, int eb) {
    const LeafTriangles la = sa_.leaf(ea);
    const LeafTriangles lb = sb_.leaf(eb);
    const double reach = 2.0 * (la.radius + lb.radius) + request_.tolerance;
    // Only curves need the overlap told apart (the haptic tick asks for none).
    LeafPairFindings found =
        leaf_crossings(la, lb, reach, on_plane_, coincide_ ? &*coincide_ : nullptr);
    return keep_findings(ea, eb, la, lb, std::move(found), request_.tolerance, reach);
  }

  /// Refines a segment's ends onto both exact surfaces, an end on an edge of
  /// either leaf along that edge (pin_to_leaf_edge); false at the first end
  /// that does not converge near the leaves (the pair is then split, so the
  /// other end is not tried). An end on an edge the leaf pair across it has
  /// refined already takes that crossing.
  bool refine_ends(detail::Segment& seg, const LeafTriangles& la, const LeafTriangles& lb,
                   double reach) {
    for (std::size_t k = 0; k < 2; ++k) {
      Eigen::Vector2d uv_a = seg.uv_a[k], uv_b = seg.uv_b[k];
      const int fixed = pin_to_leaf_edge(uv_a, la.rect, uv_b, lb.rect);
      const PairPoint start{seg.points[k], uv_a, uv_b};
      std::optional<RefinedPair> r;
      if (const RefinedPair* kept = fixed >= 0 ? edge_crossings_->find(start, fixed) : nullptr) {
        if ((kept->point - start.point).norm() <= reach) r = *kept;
      } else {
        r = refine_near(*exact_, start, true, reach, fixed);
        if (r && fixed >= 0) edge_crossings_->keep(start, fixed, *r);
      }
      if (!r) return false;
      seg.points[k] = r->point;
      seg.uv_a[k] = r->uv_a;
      seg.uv_b[k] = r->uv_b;
      seg.tangents[k] = r->tangent;
    }
    return true;
  }

  /// A transversal pair (see transversal()) as a leaf: its triangles' crossings
  /// with every end point refined onto both exact surfaces, which the
  /// densifier then follows between them. False, with nothing kept, when a
  /// leaf edge could hide an arc's end (edge_may_hide_crossing) or a point
  /// does not refine near its leaves: the pair is split instead.
  bool coarse_leaf_pair(int ea, const View& va, int eb, const View& vb) {
    const LeafTriangles la = sa_.leaf(ea);
    const LeafTriangles lb = sb_.leaf(eb);
    const double eps = request_.tolerance;
    const double reach = 2.0 * (la.radius + lb.radius) + eps;
    LeafPairFindings found = leaf_crossings(la, lb, reach, on_plane_, &*coincide_);
    // An end refined out of either leaf is a crossing of another pair: the
    // triangles crossed where the exact surfaces do not (an arc that bulges
    // across a leaf edge within the flatness), and the pair is split.
    for (detail::Segment& seg : found.segments) {
      if (!refine_ends(seg, la, lb, reach)) return false;
      for (std::size_t k = 0; k < 2; ++k)
        if (!inside(la.rect, seg.uv_a[k]) || !inside(lb.rect, seg.uv_b[k])) return false;
      seg.pinned = true;
    }
    const double band = va.flatness + vb.flatness + on_plane_;
    if (!arc_ends_accounted(ea, eb, la, lb, found.segments, band)) return false;
    // The contact takes the longest segment's refined end: a point of the
    // exact curve inside both leaves, which needs no refinement of its own.
    if (found.contact && found.contact->crossing && !found.segments.empty()) {
      const auto longest = std::max_element(found.segments.begin(), found.segments.end(),
                                            [](const detail::Segment& x, const detail::Segment& y) {
                                              return (x.points[1] - x.points[0]).squaredNorm() <
                                                     (y.points[1] - y.points[0]).squaredNorm();
                                            });
      Contact& c = found.contact->leaf.contact;
      c.point = longest->points[0];
      c.uv_a = longest->uv_a[0];
      c.uv_b = longest->uv_b[0];
      found.contact->refined = true;
    }
    ++counters_.leaf_pairs;
    // Its triangles stray up to its flatness from the patches: surfaces that
    // come within eps/3 have triangles this close.
    const double near_touch = std::max(eps, eps / 3.0 + va.flatness + vb.flatness);
    keep_findings(ea, eb, la, lb, std::move(found), near_touch, reach);
    return true;
  }

  /// Every arc of a transversal pair runs between two ends where an edge
  /// curve of one leaf meets the other's patch. True when no arc can hide
  /// beside the refined segments `found`: every edge holding a segment's end meets
  /// the other patch at most once (crosses_at_most_once, along the other's
  /// normal cone axis), and of the edges without one at most one comes
  /// within `band` of the other leaf's triangles (edge_may_hide_crossing:
  /// where an arc's end must lie), and that one meets the other patch at
  /// most once; so a hidden arc, which needs two ends, has nowhere to end.
  /// The found ends must pair up (an even count of distinct ones).
  /// Before 2026-12-02 any edge within `band` split a pair without segments,
  /// and nothing was checked beside found segments (an arc 0.2 mm beside a
  /// found one was lost).
  bool arc_ends_accounted(int ea, int eb, const LeafTriangles& la, const LeafTriangles& lb,
                          const std::vector<detail::Segment>& found, double band) {
    // Edges 0 to 3 are a's in ring order (PatchEdge), 4 to 7 b's. An end lies on an edge when it
    // holds that edge's parameter exactly: refine_ends pins an end to the edge it crossed and keeps
    // it there (an end near an edge by rounding only, as on a diagonal near a corner, marks
    // nothing, and that edge is then tested as one without an end).
    std::array<const Eigen::Vector3d*, 8> end_on{};
    std::array<const Eigen::Vector3d*, 16> ends{};  // distinct ends on edges
    std::size_t end_count = 0;
    const double same = 1e-3 * request_.tolerance;
    const auto mark = [&](const Eigen::Vector2d& uv, const ParamRect& r, std::size_t first,
                          const Eigen::Vector3d& point) {
      const std::array<bool, 4> on{uv[1] == r.v0, uv[0] == r.u1, uv[1] == r.v1, uv[0] == r.u0};
      bool marked = false;
      for (std::size_t k = 0; k < 4; ++k) {
        if (!on[k]) continue;
        const Eigen::Vector3d*& kept = end_on[first + k];
        if (kept && (*kept - point).norm() > same) return false;  // two ends on one edge
        kept = &point;
        marked = true;
      }
      if (!marked) return true;
      for (std::size_t k = 0; k < end_count; ++k)
        if ((*ends[k] - point).norm() <= same) return true;
      if (end_count == ends.size()) return false;
      ends[end_count++] = &point;
      return true;
    };
    for (const detail::Segment& seg : found)
      for (std::size_t k = 0; k < 2; ++k)
        if (!mark(seg.uv_a[k], la.rect, 0, seg.points[k]) ||
            !mark(seg.uv_b[k], lb.rect, 4, seg.points[k]))
          return false;
    // Every arc has two distinct ends: an odd count means the segments
    // folded back onto one end (triangles crossing an edge twice where the
    // surface crosses it once) and the arc's other end is not accounted for.
    if (end_count % 2 != 0) return false;
    const Eigen::Vector3d& axis_a = sa_.cone(ea)->axis;
    const Eigen::Vector3d& axis_b = sb_.cone(eb)->axis;
    const auto once = [&](std::size_t e) {
      const auto edge = static_cast<PatchEdge>(e % 4);
      return e < 4 ? crosses_at_most_once(sa_.edge_rise(ea, edge, axis_b), sb_.chord_lean(eb))
                   : crosses_at_most_once(sb_.edge_rise(eb, edge, axis_a), sa_.chord_lean(ea));
    };
    int near_without_end = 0;
    for (std::size_t e = 0; e < 8; ++e) {
      if (end_on[e]) {
        if (!once(e)) return false;
        continue;
      }
      const bool near = e < 4 ? edge_may_hide_crossing(la, e, lb, band)
                              : edge_may_hide_crossing(lb, e - 4, la, band);
      if (near && (++near_without_end > 1 || !once(e))) return false;
    }
    return true;
  }

  /// A crossing that ends on an edge of a's leaf (else of b's) is put exactly
  /// on it; returns the parameter to hold there (0 to 3: u_a, v_a, u_b, v_b),
  /// -1 for an end inside both leaves (on a triangle's diagonal). Refined
  /// along the edge, the ends that two neighbouring leaves share land on the
  /// same point of the curve even where the leaves differ in size.
  static int pin_to_leaf_edge(Eigen::Vector2d& uv_a, const ParamRect& ra, Eigen::Vector2d& uv_b,
                              const ParamRect& rb) {
    const auto pin = [](Eigen::Vector2d& uv, const ParamRect& r, int first) {
      const double near_u = 1e-12 * r.width(), near_v = 1e-12 * r.height();
      for (const double edge : {r.u0, r.u1}) {
        if (std::abs(uv[0] - edge) <= near_u) {
          uv[0] = edge;
          return first;
        }
      }
      for (const double edge : {r.v0, r.v1}) {
        if (std::abs(uv[1] - edge) <= near_v) {
          uv[1] = edge;
          return first + 1;
        }
      }
      return -1;
    };
    const int on_a = pin(uv_a, ra, 0);
    return on_a >= 0 ? on_a : pin(uv_b, rb, 2);
  }

  /// Keeps a leaf pair's segments and its contact (a crossing, else a
  /// near-touch where its triangles come within `near_touch`); true when
  /// it has a contact.
  bool keep_findings(int ea, int eb, const LeafTriangles& la, const LeafTriangles& lb,
                     LeafPairFindings found, double near_touch, double reach) {
    counters_.triangle_tests += found.triangle_tests;
    segments.insert(segments.end(), found.segments.begin(), found.segments.end());
    const bool crossing = found.contact.has_value();
    crossed_ = crossed_ || crossing;
    if (!crossing && !request_.first_crossing_only)
      found.contact = leaf_near_touch(la, lb, near_touch);
    // Kept for the way unless the pair ends farther apart than any point of b
    // moved: then the two never met (a pair without a near-touch is more than
    // eps apart, which is at least that far here).
    if (keep_near_ && !crossing) {
      const bool never_met = found.contact ? -found.contact->leaf.contact.depth > motion_->travel
                             : request_.first_crossing_only
                                 ? leaves_farther_than(la, lb, motion_->travel)
                                 : true;
      if (!never_met) near_.emplace_back(ea, eb);
    }
    if (!found.contact) return false;
    found.contact->reach = reach;
    found.contact->leaf.rect = la.rect;
    pending.add(*found.contact);
    return true;
  }

  /// The way's descent reached a leaf pair: true when it meets on the motion.
  bool way_leaf_pair(int ea, int eb) {
    const LeafTriangles la = sa_.leaf(ea);
    const LeafTriangles lb = sb_.leaf(eb);
    // Placed at the end: farther apart than any point of b moved, never met.
    // (The pairs the end's descent kept passed this or a stricter test.)
    if (leaves_farther_than(la, lb, motion_->travel)) return false;
    return meets_on_the_way(ea, eb, la, lb);
  }

  /// True when the leaf pair meets somewhere on the motion (the end was
  /// found clear by a placed descent): the meeting is a crossing on a.
  bool meets_on_the_way(int ea, int eb, const LeafTriangles& la, const LeafTriangles& lb) {
    std::optional<PendingContact> c = swept_crossing(ea, eb, la, lb);
    if (!c) return false;
    c->reach = 2.0 * (la.radius + lb.radius) + request_.tolerance;
    c->leaf.rect = la.rect;
    pending.add(*c);
    return true;
  }

  /// A crossing (depth 0) on a's leaf where b's leaf meets it during the
  /// motion though not at its end.
  std::optional<PendingContact> swept_crossing(int ea, int eb, const LeafTriangles& la,
                                               const LeafTriangles& lb) {
    detail::SweptLeafPair pair;
    pair.a = sa_.corners(ea);
    pair.b_own = sb_.own_corners(eb);
    pair.b_end = sb_.corners(eb);
    for (std::size_t k = 0; k < 4; ++k) {
      pair.b_start[k] = motion_->start(pair.b_own[k]);
      pair.a_in_b_start[k] = motion_->start_inverse(pair.a[k]);
      pair.a_in_b_end[k] = motion_->end_inverse(pair.a[k]);
    }
    const std::optional<detail::SweptHit> hit = detail::swept_leaves_meet(pair);
    if (!hit) return std::nullopt;
    PendingContact c;
    c.leaf.contact.point = hit->point;
    c.leaf.contact.uv_a = param_of(la.params[static_cast<std::size_t>(hit->triangle)], hit->bary);
    c.leaf.contact.uv_b =
        param_of(lb.params[static_cast<std::size_t>(hit->triangle_b)], hit->bary_b);
    c.crossing = true;
    return c;
  }

  /// b's motion in a swept query, and its inverse at both ends (a's corners
  /// seen from b).
  struct SweptMotion {
    Rigid start, start_inverse, end_inverse;
    double travel;  // the farthest any point of b moves [mm]
  };

  /// Coarse leaves are flat to this fraction of the pair's size (or to eps).
  static constexpr double kCoarseFraction = 1e-3;
  /// Least angle between the two sides' normals for a transversal leaf [rad]
  /// (10 degrees): the coarse triangles' crossing lies within their flatness
  /// over its sine (5.8x) of the exact curve. Any positive angle rules out
  /// loops and tangency; 15 degrees left the flatter stretches of curves to
  /// eps/3 leaves (3 to 11x slower on the random pairs at 1e-7), and 5 or 2
  /// degrees cost more in ends that fail to refine from that far (the pair is
  /// then split) than they saved.
  static constexpr double kTransversalAngle = 0.17453292519943295;

  const CollisionRequest& request_;
  QueryCounters& counters_;
  const SurfacePair* exact_;                             // for coarse leaves' refinement
  std::optional<detail::EdgeCrossings> edge_crossings_;  // with exact_: ends refined on leaf edges
  double coarse_;                                        // see coarse_tolerance()
  Side sa_;
  Side sb_;
  double on_plane_;                    // see on_plane_distance
  double apart_;                       // pairs farther apart than this are skipped
  bool way_;                           // Pass::way
  std::optional<SweptMotion> motion_;  // a swept query's
  bool keep_near_ = false;             // the end's descent keeps near_ for the way
  bool crossed_ = false;
  std::optional<CoincidenceTest> coincide_;  // curves only: crossings where faces coincide
  std::vector<std::pair<int, int>> near_;    // leaf pairs that may have met on the way
};

}  // namespace

namespace {

CollisionResult collide_placed(const SurfaceHierarchy& ha, const SurfaceHierarchy& hb,
                               const std::optional<Rigid>& placed_b,
                               const CollisionRequest& request,
                               const std::optional<Sweep>& sweep = std::nullopt) {
  CollisionResult result;
  // The tolerance must suit both surfaces.
  result.status = check_request(request, ha);
  if (result.status.ok()) result.status = check_request(request, hb);
  if (!result.status.ok()) return result;
  // Refinement and penetration work on b's exact surface in a's frame.
  const bool exact_b = request.refine || request.compute_depth;
  BSplineSurface moved_b;
  if (placed_b && exact_b) {
    moved_b = hb.surface();
    moved_b.control_points = ((hb.surface().control_points * placed_b->R.transpose()).rowwise() +
                              placed_b->p.transpose())
                                 .eval();
  }
  // The scale bounds refinement only: a pass over every pole, skipped by the
  // haptic proxies' many unrefined queries.
  const BSplineSurface& exact_surface_b = placed_b && exact_b ? moved_b : hb.surface();
  PatchEvaluator eval_a(ha.surface(), ha.operators()), eval_b(exact_surface_b, hb.operators());
  const SurfacePair pair{eval_a, eval_b,
                         request.refine ? scale_of(ha.surface(), hb.surface())
                                        : std::numeric_limits<double>::quiet_NaN()};
  PairDescent descent(ha, hb, placed_b, sweep, PairDescent::Pass::end, request, result.counters,
                      &pair);
  descent.run();
  // Swept: the way matters only when the end crosses nowhere. Bounds over the
  // whole motion reach many more pairs, so a motion longer than eps gets its
  // own descent, second, which stops at the first pair that meets.
  if (sweep && !descent.crossed()) {
    if (descent.kept_the_way()) {
      descent.meet_kept_pairs_on_the_way();
    } else {
      PairDescent way(ha, hb, placed_b, sweep, PairDescent::Pass::way, request, result.counters);
      way.run();
      descent.pending.append(way.pending);
    }
  }
  if (request.curves) {
    detail::ChainedCurves chained = detail::chain_segments(descent.segments, request.tolerance);
    result.curves = std::move(chained.curves);
    // Refinement keeps each curve's end points, so the bridge may reach as
    // far from them as refinement may move them (from a transversal leaf's
    // end, to the nearest end facing it only: EndReaches). Along an edge two
    // faces share, the leaves' triangles touch rather than cross and their
    // segments are scattered: the bridge joins the pieces along the edge.
    std::vector<detail::EndReaches> end_reaches;
    if (request.refine) {
      for (std::size_t ci = 0; ci < result.curves.size(); ++ci) {
        IntersectionCurve& c = result.curves[ci];
        c = refine_curve(pair, std::move(c), chained.reaches[ci], chained.pinned[ci],
                         chained.tangents[ci], request.tolerance);
        end_reaches.push_back({chained.reaches[ci].front(), chained.reaches[ci].back(),
                               chained.pinned[ci].front(), chained.pinned[ci].back()});
      }
    }
    // A yes/no test needs only whether there is a curve.
    if (!request.first_crossing_only)
      result.curves = detail::tidy_curves(
          std::move(result.curves), request.tolerance,
          request.refine ? bridge_for(pair, request.tolerance) : detail::GapBridge{},
          std::move(end_reaches),
          request.refine ? march_for(pair, request.tolerance) : detail::EndMarch{});
  }
  std::vector<LeafContact>& leaves = descent.pending.leaves;
  if (request.refine)
    for (std::size_t i = 0; i < leaves.size(); ++i)
      refine_contact(pair, leaves[i].contact, descent.pending.origins[i]);
  std::vector<LeafContact> off_material = take_off_material(descent.pending, request.material_a);
  // Penetration needs each region's full extent, so trim only after adding it.
  const bool penetration = request.compute_depth && !request.first_crossing_only;
  ContactRegions regions =
      group_regions(leaves, penetration ? std::numeric_limits<int>::max() : request.max_contacts);
  result.contacts = std::move(regions.contacts);
  result.region_count = regions.region_count;
  if (penetration) {
    add_penetration_contacts(pair.a(), pair.b(), result.contacts);
    rank_regions(result.contacts, result.region_count, request.max_contacts);
  }
  for (Contact& c : result.contacts) c = with_frame(pair.a(), c);
  if (!off_material.empty()) {
    result.off_material = group_regions(off_material, request.max_contacts).contacts;
    for (Contact& c : result.off_material) c = with_frame(pair.a(), c);
  }
  return result;
}

}  // namespace

CollisionResult collide(const SurfaceHierarchy& ha, const SurfaceHierarchy& hb,
                        const CollisionRequest& request) {
  return collide_placed(ha, hb, std::nullopt, request);
}

CollisionResult collide(const SurfaceHierarchy& ha, const SurfaceHierarchy& hb, const Pose& X_AB,
                        const CollisionRequest& request) {
  return collide_placed(ha, hb, Rigid{X_AB.R.normalized().toRotationMatrix(), X_AB.p}, request);
}

CollisionResult collide_swept(const SurfaceHierarchy& ha, const SurfaceHierarchy& hb,
                              const Pose& X_AB_from, const Pose& X_AB_to,
                              const CollisionRequest& request) {
  const Eigen::Quaterniond from = X_AB_from.R.normalized(), to = X_AB_to.R.normalized();
  // A point x of b turns on an arc of radius |x| through the angle between
  // the rotations; the arc strays from its chord by |x| (1 - cos(angle / 2)).
  const double radius = hb.surface().control_points.rowwise().norm().maxCoeff();
  const double angle = from.angularDistance(to);
  const double sagitta = radius * (1.0 - std::cos(0.5 * angle));
  // On its straight line a point is within half its chord (at most the
  // translation plus the rotation's chord) of the line's midpoint, which is
  // within the sagitta of the point's halfway position.
  const double turn_chord = 2.0 * radius * std::sin(0.5 * angle);
  const double chord = (X_AB_to.p - X_AB_from.p).norm() + turn_chord;
  const Eigen::Quaterniond middle = from.slerp(0.5, to);
  return collide_placed(
      ha, hb, Rigid{to.toRotationMatrix(), X_AB_to.p}, request,
      Sweep{Rigid{from.toRotationMatrix(), X_AB_from.p},
            Rigid{middle.toRotationMatrix(), 0.5 * (X_AB_from.p + X_AB_to.p)},
            0.5 * (X_AB_to.p - X_AB_from.p), 0.5 * turn_chord + sagitta, sagitta, chord});
}

}  // namespace argil
