#include "argil/core/collision/implicit_contact.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>
#include <queue>
#include <set>
#include <tuple>

#include "argil/core/collision/contact_regions.hpp"
#include "argil/core/collision/patch_minimize.hpp"
#include "argil/core/geometry/triangle_distance.hpp"

namespace argil {

namespace {

Contact make_contact(const BSplineSurface& s, const PatchMinimum& m) {
  Contact c;
  c.point = m.derivatives.point;
  c.uv_a = m.uv;
  c.normal = unit_normal(m.derivatives);
  // At a pole: the limit normal (needs second derivatives, so only here).
  if (c.normal.squaredNorm() == 0.0) c.normal = unit_normal(s, m.uv[0], m.uv[1]);
  c.tangent_u = m.derivatives.du;
  c.tangent_v = m.derivatives.dv;
  c.depth = -m.value;
  return c;
}

/// Tools without an exact triangle bound descend at most this many levels
/// below the first flat level before the local minimum decides.
constexpr int kExtraLevels = 4;

/// Replaces each region's first contact by its deepest point:
/// Newton on the region's leaves in order of how deep they could be (their
/// lower bounds), stopping when no leaf can be deeper than the best found.
void refine_region_heads(SurfaceHierarchy& h,
                         const std::function<DistanceSample(const Eigen::Vector3d&)>& f,
                         const std::vector<LeafContact>& leaves, CollisionResult& result) {
  std::size_t begin = 0;
  while (begin < leaves.size()) {
    std::size_t end = begin;
    while (end < leaves.size() && leaves[end].contact.region == leaves[begin].contact.region) ++end;
    std::vector<const LeafContact*> order;
    for (std::size_t i = begin; i < end; ++i) order.push_back(&leaves[i]);
    std::stable_sort(order.begin(), order.end(), [](const LeafContact* a, const LeafContact* b) {
      return a->value_lower_bound < b->value_lower_bound;
    });
    Contact best = leaves[begin].contact;  // the deepest sample
    for (const LeafContact* leaf : order) {
      if (-leaf->value_lower_bound <= best.depth) break;
      const BezierPatch* patch = leaf->node >= 0 ? &h.node(leaf->node).patch : nullptr;
      const PatchMinimum m =
          minimize_on_patch(h.surface(), leaf->u0, leaf->u1, leaf->v0, leaf->v1, f, nullptr, patch);
      if (-m.value > best.depth) {
        best = make_contact(h.surface(), m);
        best.region = leaves[begin].contact.region;
      }
    }
    for (Contact& c : result.contacts) {
      if (c.region == best.region) {
        c = best;
        break;
      }
    }
    begin = end;
  }
}

}  // namespace

CollisionResult collide(SurfaceHierarchy& h, const ImplicitTool& tool,
                        const CollisionRequest& request) {
  CollisionResult result;
  result.status = check_request(request, h);
  if (!result.status.ok()) return result;
  const double eps = request.tolerance;
  const double lipschitz = tool.lipschitz();
  const auto f = [&tool](const Eigen::Vector3d& x) { return tool.distance(x); };
  std::vector<LeafContact> leaves;
  struct Pending {
    int id;
    int flat_level;  // level at which this branch first became flat, or -1
  };
  std::vector<Pending> stack;
  // Blocks of elements first: only elements the tool may reach become roots.
  std::vector<int> blocks{0};
  while (!blocks.empty()) {
    const int b = blocks.back();
    blocks.pop_back();
    const ElementBlock& block = h.block(b, &result.counters);
    if (tool.value(block.bound.center) - lipschitz * block.bound.radius > eps) continue;
    if (block.element_node >= 0) {
      stack.push_back({block.element_node, -1});
      continue;
    }
    for (int c : block.children)
      if (c >= 0) blocks.push_back(c);
  }
  while (!stack.empty()) {
    const auto [id, flat_since] = stack.back();
    stack.pop_back();
    const HierarchyNode& node = h.node(id, &result.counters);
    const double reach = lipschitz * node.bound.radius;
    const double centre_value = tool.value(node.bound.center);
    const double lower = centre_value - reach;
    if (lower > eps) continue;
    if (centre_value + reach <= 0.0) {
      // The whole sub-patch is inside the tool: one contact stands for it;
      // descending would only multiply contacts.
      ++result.counters.leaf_pairs;
      const PatchMinimum m = best_sample_on_patch(h.surface(), node.u0, node.u1, node.v0, node.v1,
                                                  f, &node.bound.corners, &node.patch);
      leaves.push_back(
          {make_contact(h.surface(), m), node.u0, node.u1, node.v0, node.v1, lower, id});
      continue;
    }
    const bool flat = node.bound.flatness <= eps || node.level >= SurfaceHierarchy::kMaxLevel;
    if (!flat && tool.exact_triangle_bound() && node.bound.flatness < node.bound.radius) {
      // Corner triangles less the flatness bound the patch more tightly than
      // its sphere once it is moderately flat: prune before splitting.
      const auto& c = node.bound.corners;
      const double triangles = std::min(tool.lower_bound_on_triangle(c[0], c[1], c[3]),
                                        tool.lower_bound_on_triangle(c[0], c[3], c[2]));
      if (triangles - lipschitz * node.bound.flatness > eps) continue;
    }
    if (flat) {
      // The patch is within `flatness` of its two corner triangles.
      const auto& c = node.bound.corners;
      const double triangles = std::min(tool.lower_bound_on_triangle(c[0], c[1], c[3]),
                                        tool.lower_bound_on_triangle(c[0], c[3], c[2]));
      const double leaf_lower = std::max(lower, triangles - lipschitz * node.bound.flatness);
      if (leaf_lower > eps) continue;
      ++result.counters.leaf_pairs;
      ++result.counters.triangle_tests;
      // A sample in contact settles the leaf; Newton only decides the others
      // (region heads are refined after grouping).
      const PatchMinimum sample = best_sample_on_patch(
          h.surface(), node.u0, node.u1, node.v0, node.v1, f, &node.bound.corners, &node.patch);
      if (sample.value <= eps) {
        leaves.push_back({make_contact(h.surface(), sample), node.u0, node.u1, node.v0, node.v1,
                          leaf_lower, id});
        continue;
      }
      const PatchMinimum m = minimize_on_patch(h.surface(), node.u0, node.u1, node.v0, node.v1, f,
                                               &node.bound.corners, &node.patch);
      if (m.value <= eps) {
        leaves.push_back(
            {make_contact(h.surface(), m), node.u0, node.u1, node.v0, node.v1, leaf_lower, id});
        continue;
      }
      if (reach <= eps || node.level >= SurfaceHierarchy::kMaxLevel) continue;
      // Tools without an exact triangle bound stop a few levels below
      // flatness: the local minimum then decides (see docs/collision.md).
      if (!tool.exact_triangle_bound() && flat_since >= 0 &&
          node.level >= flat_since + kExtraLevels) {
        continue;
      }
    }
    const int flat_level = flat ? (flat_since >= 0 ? flat_since : node.level) : -1;
    // h.child() may reallocate the node pool: `node` is not used after this.
    for (int hu = 1; hu >= 0; --hu)
      for (int hv = 1; hv >= 0; --hv) stack.push_back({h.child(id, hu, hv), flat_level});
  }
  group_regions(leaves, request.max_contacts, result);
  if (request.refine) refine_region_heads(h, f, leaves, result);
  // Neighbouring leaves can give the same point (a shared corner or edge):
  // keep its first, deepest-first listing.
  std::vector<Contact> unique;
  std::set<std::pair<double, double>> seen;
  for (const Contact& c : result.contacts) {
    if (seen.insert({c.uv_a[0], c.uv_a[1]}).second) unique.push_back(c);
  }
  result.contacts = std::move(unique);
  return result;
}

ClosestPoint closest_point(SurfaceHierarchy& h, const Eigen::Vector3d& p,
                           const CollisionRequest& request) {
  ClosestPoint best;
  best.status = check_request(request, h);
  if (!best.status.ok()) {
    best.distance = best.signed_distance = std::numeric_limits<double>::quiet_NaN();
    return best;
  }
  best.distance = std::numeric_limits<double>::infinity();
  const double eps = request.tolerance;
  const auto f = [&p](const Eigen::Vector3d& x) {
    DistanceSample s;  // half squared distance: smooth, Hessian I
    s.value = 0.5 * (x - p).squaredNorm();
    s.gradient = x - p;
    s.hessian.setIdentity();
    return s;
  };
  // Lower bound of |p - S| over a node: the sphere, and the corner triangles
  // less the flatness (exact point-triangle distances).
  const auto node_lower = [&p](const PatchBound& b) {
    double lower = (p - b.center).norm() - b.radius;
    if (std::isfinite(b.flatness)) {
      const auto& c = b.corners;
      const double triangles =
          std::min((closest_point_on_triangle(p, c[0], c[1], c[3]) - p).norm(),
                   (closest_point_on_triangle(p, c[0], c[3], c[2]) - p).norm());
      lower = std::max(lower, triangles - b.flatness);
    }
    return std::max(0.0, lower);
  };
  // Entries: blocks as -(id + 1), hierarchy nodes as id >= 0. Equal lower
  // bounds (0 for every node holding p) are ordered by the node's place in
  // the tree, not its id, so the answer does not depend on the order in which
  // earlier queries created nodes (ids change when the pool is released).
  struct Entry {
    double lower;
    int level;  // -1 for blocks
    double u0, v0;
    int entry;
    bool operator>(const Entry& o) const {
      return std::tie(lower, level, u0, v0, entry) >
             std::tie(o.lower, o.level, o.u0, o.v0, o.entry);
    }
  };
  const auto block_entry = [](double lower, int block) {
    return Entry{lower, -1, static_cast<double>(block), 0.0, -block - 1};
  };
  const auto node_entry = [](double lower, const HierarchyNode& n, int id) {
    return Entry{lower, n.level, n.u0, n.v0, id};
  };
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
  queue.push(block_entry(node_lower(h.block(0, &best.counters).bound), 0));
  Eigen::Vector2d best_uv(h.surface().domain_start(Direction::u),
                          h.surface().domain_start(Direction::v));
  const auto offer = [&](const Eigen::Vector3d& x, const Eigen::Vector2d& uv) {
    const double d = (x - p).norm();
    if (d < best.distance) {
      best.distance = d;
      best_uv = uv;
    }
  };
  while (!queue.empty()) {
    const double lower = queue.top().lower;
    const int entry = queue.top().entry;
    queue.pop();
    if (lower >= best.distance - eps) break;  // nothing left beats the best by eps
    if (entry < 0) {
      const ElementBlock& block = h.block(-entry - 1, &best.counters);
      if (block.element_node >= 0) {
        const HierarchyNode& n = h.node(block.element_node, &best.counters);
        queue.push(node_entry(node_lower(n.bound), n, block.element_node));
        continue;
      }
      for (int c : block.children) {
        if (c < 0) continue;
        const double child_lower = node_lower(h.block(c, &best.counters).bound);
        if (child_lower < best.distance - eps) queue.push(block_entry(child_lower, c));
      }
      continue;
    }
    const int id = entry;
    const HierarchyNode& node = h.node(id, &best.counters);
    // Patch corners lie on the surface: free upper bounds.
    offer(node.bound.corners[0], {node.u0, node.v0});
    offer(node.bound.corners[1], {node.u1, node.v0});
    offer(node.bound.corners[2], {node.u0, node.v1});
    offer(node.bound.corners[3], {node.u1, node.v1});
    const bool leaf = node.bound.flatness <= eps || node.bound.radius <= eps ||
                      node.level >= SurfaceHierarchy::kMaxLevel;
    if (leaf) {
      ++best.counters.leaf_pairs;
      const PatchMinimum m = minimize_on_patch(h.surface(), node.u0, node.u1, node.v0, node.v1, f,
                                               &node.bound.corners, &node.patch);
      offer(m.derivatives.point, m.uv);
      continue;
    }
    // h.child() may reallocate the node pool: `node` is not used after this.
    for (int hu = 0; hu < 2; ++hu) {
      for (int hv = 0; hv < 2; ++hv) {
        const int c = h.child(id, hu, hv);
        const HierarchyNode& child = h.node(c, &best.counters);
        const double child_lower = node_lower(child.bound);
        if (child_lower < best.distance - eps) queue.push(node_entry(child_lower, child, c));
      }
    }
  }
  const SurfaceDerivatives d = evaluate_derivatives(h.surface(), best_uv[0], best_uv[1], 1);
  best.uv = best_uv;
  best.point = d.point;
  best.distance = (p - d.point).norm();
  best.normal = unit_normal(d);
  if (best.normal.squaredNorm() == 0.0)
    best.normal = unit_normal(h.surface(), best_uv[0], best_uv[1]);
  best.signed_distance = (p - d.point).dot(best.normal) >= 0.0 ? best.distance : -best.distance;
  return best;
}

}  // namespace argil
