#include "argil/core/implicit_contact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <queue>
#include <tuple>

#include "argil/core/patch_minimize.hpp"

namespace argil {

namespace {

struct LeafContact {
  Contact contact;
  double u0, u1, v0, v1;  // the leaf's parameter rectangle
};

bool rectangles_touch(const LeafContact& a, const LeafContact& b) {
  return a.u0 <= b.u1 && b.u0 <= a.u1 && a.v0 <= b.v1 && b.v0 <= a.v1;
}

int find(std::vector<int>& parent, int i) {
  while (parent[static_cast<std::size_t>(i)] != i) {
    parent[static_cast<std::size_t>(i)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
    i = parent[static_cast<std::size_t>(i)];
  }
  return i;
}

/// Groups leaf contacts whose rectangles touch into regions, orders each
/// region deepest first, and keeps at most max_contacts (deepest regions first).
void group_regions(std::vector<LeafContact>& leaves, int max_contacts, CollisionResult& out) {
  const int n = static_cast<int>(leaves.size());
  std::vector<int> parent(static_cast<std::size_t>(n));
  std::iota(parent.begin(), parent.end(), 0);
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      if (rectangles_touch(leaves[static_cast<std::size_t>(i)], leaves[static_cast<std::size_t>(j)]))
        parent[static_cast<std::size_t>(find(parent, i))] = find(parent, j);
  std::vector<int> region_of_root(static_cast<std::size_t>(n), -1);
  int regions = 0;
  for (int i = 0; i < n; ++i) {
    const int root = find(parent, i);
    if (region_of_root[static_cast<std::size_t>(root)] < 0) region_of_root[static_cast<std::size_t>(root)] = regions++;
    leaves[static_cast<std::size_t>(i)].contact.region = region_of_root[static_cast<std::size_t>(root)];
  }
  std::vector<double> deepest(static_cast<std::size_t>(regions), -std::numeric_limits<double>::infinity());
  for (const LeafContact& l : leaves)
    deepest[static_cast<std::size_t>(l.contact.region)] = std::max(deepest[static_cast<std::size_t>(l.contact.region)], l.contact.depth);
  // Regions by deepest point, then contacts by depth; ties by parameters so the
  // order is deterministic.
  std::vector<int> order(static_cast<std::size_t>(regions));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return deepest[static_cast<std::size_t>(a)] > deepest[static_cast<std::size_t>(b)];
  });
  std::vector<int> rank(static_cast<std::size_t>(regions));
  for (int r = 0; r < regions; ++r) rank[static_cast<std::size_t>(order[static_cast<std::size_t>(r)])] = r;
  for (LeafContact& l : leaves) l.contact.region = rank[static_cast<std::size_t>(l.contact.region)];
  std::stable_sort(leaves.begin(), leaves.end(), [](const LeafContact& a, const LeafContact& b) {
    if (a.contact.region != b.contact.region) return a.contact.region < b.contact.region;
    if (a.contact.depth != b.contact.depth) return a.contact.depth > b.contact.depth;
    return std::tie(a.contact.uv_a[0], a.contact.uv_a[1]) < std::tie(b.contact.uv_a[0], b.contact.uv_a[1]);
  });
  out.region_count = regions;
  // Keep every region's deepest contact, then fill up to max_contacts in
  // order; the kept contacts stay grouped by region.
  std::vector<bool> keep(leaves.size(), false);
  int kept = 0;
  for (std::size_t i = 0; i < leaves.size() && kept < max_contacts; ++i) {
    if (i == 0 || leaves[i].contact.region != leaves[i - 1].contact.region) {
      keep[i] = true;
      ++kept;
    }
  }
  for (std::size_t i = 0; i < leaves.size() && kept < max_contacts; ++i) {
    if (!keep[i]) {
      keep[i] = true;
      ++kept;
    }
  }
  for (std::size_t i = 0; i < leaves.size(); ++i)
    if (keep[i]) out.contacts.push_back(leaves[i].contact);
}

Contact make_contact(const PatchMinimum& m) {
  Contact c;
  c.point = m.derivatives.point;
  c.uv_a = m.uv;
  c.normal = unit_normal(m.derivatives);
  c.tangent_u = m.derivatives.du;
  c.tangent_v = m.derivatives.dv;
  c.depth = -m.value;
  return c;
}

/// Tools without an exact triangle bound descend at most this many levels
/// below the first flat level before the local minimum decides.
constexpr int kExtraLevels = 4;

}  // namespace

CollisionResult collide(SurfaceHierarchy& h, const ImplicitTool& tool,
                        const CollisionRequest& request) {
  CollisionResult result;
  const double eps = request.tolerance;
  const double lipschitz = tool.lipschitz();
  const auto f = [&tool](const Eigen::Vector3d& x) { return tool.distance(x); };
  std::vector<LeafContact> leaves;
  struct Pending {
    int id;
    int flat_level;  // level at which this branch first became flat, or -1
  };
  std::vector<Pending> stack;
  for (auto it = h.roots().rbegin(); it != h.roots().rend(); ++it) stack.push_back({*it, -1});
  // Broad phase: the whole net's sphere.
  const PatchBound& all = h.root_bound();
  if (tool.distance(all.center).value - lipschitz * all.radius > eps) return result;
  while (!stack.empty()) {
    const auto [id, flat_since] = stack.back();
    stack.pop_back();
    const HierarchyNode& node = h.node(id, &result.counters);
    const double reach = lipschitz * node.bound.radius;
    const double lower = tool.distance(node.bound.center).value - reach;
    if (lower > eps) continue;
    if (tool.distance(node.bound.center).value + reach <= 0.0) {
      // The whole sub-patch is inside the tool: one contact at its deepest
      // point stands for it; descending would only multiply contacts.
      ++result.counters.leaf_pairs;
      const PatchMinimum m = minimize_on_patch(h.surface(), node.u0, node.u1, node.v0, node.v1, f);
      leaves.push_back({make_contact(m), node.u0, node.u1, node.v0, node.v1});
      continue;
    }
    const bool flat = node.bound.flatness <= eps || node.level >= SurfaceHierarchy::kMaxLevel;
    if (flat) {
      // The patch is within `flatness` of its two corner triangles.
      const auto& c = node.bound.corners;
      const double triangles = std::min(tool.lower_bound_on_triangle(c[0], c[1], c[3]),
                                        tool.lower_bound_on_triangle(c[0], c[3], c[2]));
      if (triangles - lipschitz * node.bound.flatness > eps) continue;
      ++result.counters.leaf_pairs;
      ++result.counters.triangle_tests;
      const PatchMinimum m = minimize_on_patch(h.surface(), node.u0, node.u1, node.v0, node.v1, f);
      if (m.value <= eps) {
        leaves.push_back({make_contact(m), node.u0, node.u1, node.v0, node.v1});
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
  // Neighbouring leaves can converge to the same point on their shared edge.
  std::vector<LeafContact> unique;
  for (const LeafContact& l : leaves) {
    const bool seen = std::any_of(unique.begin(), unique.end(), [&](const LeafContact& k) {
      return (k.contact.uv_a - l.contact.uv_a).norm() == 0.0;
    });
    if (!seen) unique.push_back(l);
  }
  group_regions(unique, request.max_contacts, result);
  return result;
}

ClosestPoint closest_point(SurfaceHierarchy& h, const Eigen::Vector3d& p,
                           const CollisionRequest& request) {
  ClosestPoint best;
  best.distance = std::numeric_limits<double>::infinity();
  const double eps = request.tolerance;
  const auto f = [&p](const Eigen::Vector3d& x) {
    DistanceSample s;  // half squared distance: smooth, Hessian I
    s.value = 0.5 * (x - p).squaredNorm();
    s.gradient = x - p;
    s.hessian.setIdentity();
    return s;
  };
  using Entry = std::pair<double, int>;  // lower bound, node
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
  for (int root : h.roots()) {
    const HierarchyNode& n = h.node(root, &best.counters);
    queue.push({std::max(0.0, (p - n.bound.center).norm() - n.bound.radius), root});
  }
  Eigen::Vector2d best_uv(h.surface().domain_start(Direction::u), h.surface().domain_start(Direction::v));
  while (!queue.empty()) {
    const auto [lower, id] = queue.top();
    queue.pop();
    if (lower >= best.distance - eps) break;  // nothing left beats the best by eps
    const HierarchyNode& node = h.node(id, &best.counters);
    // Patch corners lie on the surface: a free upper bound.
    const Eigen::Vector2d corner_uv[4] = {{node.u0, node.v0}, {node.u1, node.v0}, {node.u0, node.v1}, {node.u1, node.v1}};
    for (int k = 0; k < 4; ++k) {
      const double d = (node.bound.corners[k] - p).norm();
      if (d < best.distance) {
        best.distance = d;
        best_uv = corner_uv[k];
      }
    }
    const bool leaf = node.bound.flatness <= eps || node.bound.radius <= eps ||
                      node.level >= SurfaceHierarchy::kMaxLevel;
    if (leaf) {
      ++best.counters.leaf_pairs;
      const PatchMinimum m = minimize_on_patch(h.surface(), node.u0, node.u1, node.v0, node.v1, f);
      const double d = std::sqrt(2.0 * std::max(0.0, m.value));
      if (d < best.distance) {
        best.distance = d;
        best_uv = m.uv;
      }
      continue;
    }
    for (int hu = 0; hu < 2; ++hu) {
      for (int hv = 0; hv < 2; ++hv) {
        const int c = h.child(id, hu, hv);
        const HierarchyNode& child = h.node(c, &best.counters);
        const double child_lower = std::max(0.0, (p - child.bound.center).norm() - child.bound.radius);
        if (child_lower < best.distance - eps) queue.push({child_lower, c});
      }
    }
  }
  const SurfaceDerivatives d = evaluate_derivatives(h.surface(), best_uv[0], best_uv[1], 1);
  best.uv = best_uv;
  best.point = d.point;
  best.distance = (p - d.point).norm();
  best.normal = unit_normal(d);
  best.signed_distance = (p - d.point).dot(best.normal) >= 0.0 ? best.distance : -best.distance;
  return best;
}

}  // namespace argil
