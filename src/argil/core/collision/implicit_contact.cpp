#include "argil/core/collision/implicit_contact.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>
#include <queue>
#include <set>
#include <tuple>

#include "argil/core/collision/detail/contact_regions.hpp"
#include "argil/core/collision/detail/patch_minimize.hpp"
#include "argil/core/collision/surface_contact.hpp"
#include "argil/core/geometry/triangle_distance.hpp"

namespace argil {

namespace {

Contact make_contact(const BSplineSurface& s, const PatchMinimum& m) {
  return contact_at(s, m.uv, m.derivatives, -m.value);
}

PatchHints hints_of(const HierarchyNode& node) { return {&node.bound.corners, &node.patch}; }

/// Tools without an exact triangle bound descend at most this many levels
/// below the first flat level before the local minimum decides.
constexpr int kExtraLevels = 4;

/// Replaces each region's first contact by its deepest point:
/// Newton on the region's leaves in order of how deep they could be (their
/// lower bounds), stopping when no leaf can be deeper than the best found.
void refine_region_heads(const SurfaceHierarchy& h, const PointFunction& f,
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
      const PatchMinimum m = minimize_on_patch(h.surface(), leaf->rect, f, {nullptr, patch});
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

/// Neighbouring leaves can give the same point (a shared corner or edge):
/// keeps its first, deepest-first listing.
std::vector<Contact> unique_by_uv(const std::vector<Contact>& contacts) {
  std::vector<Contact> unique;
  std::set<std::pair<double, double>> seen;
  for (const Contact& c : contacts) {
    if (seen.insert({c.uv_a[0], c.uv_a[1]}).second) unique.push_back(c);
  }
  return unique;
}

/// The descent of collide(surface, tool): a depth-first walk from the
/// elements the tool may reach, collecting one LeafContact per leaf in contact.
class ToolDescent {
 public:
  ToolDescent(const SurfaceHierarchy& h, const ImplicitTool& tool, double eps,
              QueryCounters& counters)
      : h_(h),
        tool_(tool),
        f_([&tool](const Eigen::Vector3d& x) { return tool.distance(x); }),
        eps_(eps),
        lipschitz_(tool.lipschitz()),
        counters_(counters) {}

  std::vector<LeafContact> run() {
    push_reachable_elements();
    while (!stack_.empty()) {
      const Pending p = stack_.back();
      stack_.pop_back();
      visit(p);
    }
    return std::move(leaves_);
  }

  const PointFunction& function() const { return f_; }

 private:
  struct Pending {
    int id;
    int flat_level;  // level at which this branch first became flat, or -1
  };

  /// Blocks of elements first: only elements the tool may reach become roots.
  void push_reachable_elements() {
    std::vector<int> blocks{0};
    while (!blocks.empty()) {
      const int b = blocks.back();
      blocks.pop_back();
      const ElementBlock& block = h_.block(b, &counters_);
      if (tool_.value(block.bound.center) - lipschitz_ * block.bound.radius > eps_) continue;
      if (block.element_node >= 0) {
        stack_.push_back({block.element_node, -1});
        continue;
      }
      for (int c : block.children)
        if (c >= 0) blocks.push_back(c);
    }
  }

  /// Lower bound of the tool function on the node's two corner triangles.
  double triangles_lower(const PatchBound& b) const {
    const auto& c = b.corners;
    return std::min(tool_.lower_bound_on_triangle(c[0], c[1], c[3]),
                    tool_.lower_bound_on_triangle(c[0], c[3], c[2]));
  }

  void add_leaf(const PatchMinimum& m, const HierarchyNode& node, double lower, int id) {
    leaves_.push_back({make_contact(h_.surface(), m), node.rect, lower, id});
  }

  void visit(const Pending& p) {
    const HierarchyNode& node = h_.node(p.id, &counters_);
    const double reach = lipschitz_ * node.bound.radius;
    const double centre_value = tool_.value(node.bound.center);
    const double lower = centre_value - reach;
    if (lower > eps_) return;
    if (centre_value + reach <= 0.0) {
      // The whole sub-patch is inside the tool: one contact stands for it;
      // descending would only multiply contacts.
      ++counters_.leaf_pairs;
      add_leaf(best_sample_on_patch(h_.surface(), node.rect, f_, hints_of(node)), node, lower,
               p.id);
      return;
    }
    const bool flat = node.bound.flatness <= eps_ || node.level >= SurfaceHierarchy::kMaxLevel;
    if (!flat && tool_.exact_triangle_bound() && node.bound.flatness < node.bound.radius) {
      // Corner triangles less the flatness bound the patch more tightly than
      // its sphere once it is moderately flat: prune before splitting.
      if (triangles_lower(node.bound) - lipschitz_ * node.bound.flatness > eps_) return;
    }
    if (flat && settle_flat_leaf(node, p, lower, reach)) return;
    const int flat_level = flat ? (p.flat_level >= 0 ? p.flat_level : node.level) : -1;
    // h_.child() may reallocate the node pool: `node` is not used after this.
    for (int hu = 1; hu >= 0; --hu)
      for (int hv = 1; hv >= 0; --hv) stack_.push_back({h_.child(p.id, hu, hv), flat_level});
  }

  /// A flat node: true when it is settled (a contact, or nothing on it can be
  /// in contact), false when it must still be split.
  bool settle_flat_leaf(const HierarchyNode& node, const Pending& p, double lower, double reach) {
    // The patch is within `flatness` of its two corner triangles.
    const double leaf_lower =
        std::max(lower, triangles_lower(node.bound) - lipschitz_ * node.bound.flatness);
    if (leaf_lower > eps_) return true;
    ++counters_.leaf_pairs;
    ++counters_.triangle_tests;
    // A sample in contact settles the leaf; Newton only decides the others
    // (region heads are refined after grouping).
    const PatchMinimum sample = best_sample_on_patch(h_.surface(), node.rect, f_, hints_of(node));
    if (sample.value <= eps_) {
      add_leaf(sample, node, leaf_lower, p.id);
      return true;
    }
    const PatchMinimum m = minimize_on_patch(h_.surface(), node.rect, f_, hints_of(node));
    if (m.value <= eps_) {
      add_leaf(m, node, leaf_lower, p.id);
      return true;
    }
    if (reach <= eps_ || node.level >= SurfaceHierarchy::kMaxLevel) return true;
    // Tools without an exact triangle bound stop a few levels below
    // flatness: the local minimum then decides (see docs/collision.md).
    return !tool_.exact_triangle_bound() && p.flat_level >= 0 &&
           node.level >= p.flat_level + kExtraLevels;
  }

  const SurfaceHierarchy& h_;
  const ImplicitTool& tool_;
  PointFunction f_;
  double eps_;
  double lipschitz_;
  QueryCounters& counters_;
  std::vector<Pending> stack_;
  std::vector<LeafContact> leaves_;
};

/// Half the squared distance to p: smooth, Hessian I, same minimiser as |x - p|.
PointFunction half_squared_distance_to(const Eigen::Vector3d& p) {
  return [p](const Eigen::Vector3d& x) {
    DistanceSample s;
    s.value = 0.5 * (x - p).squaredNorm();
    s.gradient = x - p;
    s.hessian.setIdentity();
    return s;
  };
}

/// The best-first search of closest_point(). Entries: blocks as -(id + 1),
/// hierarchy nodes as id >= 0.
class ClosestSearch {
 public:
  ClosestSearch(const SurfaceHierarchy& h, const Eigen::Vector3d& p, double eps,
                QueryCounters& counters)
      : h_(h),
        p_(p),
        f_(half_squared_distance_to(p)),
        eps_(eps),
        counters_(counters),
        best_uv_(domain_of(h.surface()).lower()) {}

  /// The parameters of the closest point found (within eps of the global minimum).
  Eigen::Vector2d run() {
    queue_.push(block_entry(node_lower(h_.block(0, &counters_).bound), 0));
    while (!queue_.empty()) {
      const Entry top = queue_.top();
      queue_.pop();
      if (top.lower >= best_distance_ - eps_) break;  // nothing left beats the best by eps
      if (top.entry < 0) {
        expand_block(-top.entry - 1);
      } else {
        visit_node(top.entry);
      }
    }
    return best_uv_;
  }

 private:
  /// Equal lower bounds (0 for every node holding p) are ordered by the
  /// node's place in the tree, not its id, so the answer does not depend on
  /// the order in which earlier queries created nodes (ids change when the
  /// pool is released).
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
  static Entry block_entry(double lower, int block) {
    return Entry{lower, -1, static_cast<double>(block), 0.0, -block - 1};
  }
  static Entry node_entry(double lower, const HierarchyNode& n, int id) {
    return Entry{lower, n.level, n.rect.u0, n.rect.v0, id};
  }

  /// Lower bound of |p - S| over a node: the sphere, and the corner triangles
  /// less the flatness (exact point-triangle distances).
  double node_lower(const PatchBound& b) const {
    double lower = (p_ - b.center).norm() - b.radius;
    if (std::isfinite(b.flatness)) {
      const auto& c = b.corners;
      const double triangles =
          std::min((closest_point_on_triangle(p_, c[0], c[1], c[3]) - p_).norm(),
                   (closest_point_on_triangle(p_, c[0], c[3], c[2]) - p_).norm());
      lower = std::max(lower, triangles - b.flatness);
    }
    return std::max(0.0, lower);
  }

  void offer(const Eigen::Vector3d& x, const Eigen::Vector2d& uv) {
    const double d = (x - p_).norm();
    if (d < best_distance_) {
      best_distance_ = d;
      best_uv_ = uv;
    }
  }

  void expand_block(int id) {
    const ElementBlock& block = h_.block(id, &counters_);
    if (block.element_node >= 0) {
      const HierarchyNode& n = h_.node(block.element_node, &counters_);
      queue_.push(node_entry(node_lower(n.bound), n, block.element_node));
      return;
    }
    for (int c : block.children) {
      if (c < 0) continue;
      const double child_lower = node_lower(h_.block(c, &counters_).bound);
      if (child_lower < best_distance_ - eps_) queue_.push(block_entry(child_lower, c));
    }
  }

  void visit_node(int id) {
    const HierarchyNode& node = h_.node(id, &counters_);
    // Patch corners lie on the surface: free upper bounds.
    for (int k = 0; k < 4; ++k)
      offer(node.bound.corners[static_cast<std::size_t>(k)], node.rect.corner(k));
    const bool leaf = node.bound.flatness <= eps_ || node.bound.radius <= eps_ ||
                      node.level >= SurfaceHierarchy::kMaxLevel;
    if (leaf) {
      ++counters_.leaf_pairs;
      const PatchMinimum m = minimize_on_patch(h_.surface(), node.rect, f_, hints_of(node));
      offer(m.derivatives.point, m.uv);
      return;
    }
    // h_.child() may reallocate the node pool: `node` is not used after this.
    for (int hu = 0; hu < 2; ++hu) {
      for (int hv = 0; hv < 2; ++hv) {
        const int c = h_.child(id, hu, hv);
        const HierarchyNode& child = h_.node(c, &counters_);
        const double child_lower = node_lower(child.bound);
        if (child_lower < best_distance_ - eps_) queue_.push(node_entry(child_lower, child, c));
      }
    }
  }

  const SurfaceHierarchy& h_;
  Eigen::Vector3d p_;
  PointFunction f_;
  double eps_;
  QueryCounters& counters_;
  double best_distance_ = std::numeric_limits<double>::infinity();
  Eigen::Vector2d best_uv_;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue_;
};

}  // namespace

CollisionResult collide(const SurfaceHierarchy& h, const ImplicitTool& tool,
                        const CollisionRequest& request) {
  CollisionResult result;
  result.status = check_request(request, h);
  if (!result.status.ok()) return result;
  ToolDescent descent(h, tool, request.tolerance, result.counters);
  std::vector<LeafContact> leaves = descent.run();
  ContactRegions regions = group_regions(leaves, request.max_contacts);
  result.contacts = std::move(regions.contacts);
  result.region_count = regions.region_count;
  if (request.refine) refine_region_heads(h, descent.function(), leaves, result);
  result.contacts = unique_by_uv(result.contacts);
  return result;
}

ClosestPoint closest_point(const SurfaceHierarchy& h, const Eigen::Vector3d& p,
                           const CollisionRequest& request) {
  ClosestPoint best;
  best.status = check_request(request, h);
  if (!best.status.ok()) {
    best.distance = best.signed_distance = std::numeric_limits<double>::quiet_NaN();
    return best;
  }
  const Eigen::Vector2d uv = ClosestSearch(h, p, request.tolerance, best.counters).run();
  const SurfaceDerivatives d = evaluate_derivatives(h.surface(), uv[0], uv[1], 1);
  const Contact c = contact_at(h.surface(), uv, d, 0.0);
  best.uv = uv;
  best.point = c.point;
  best.distance = (p - c.point).norm();
  best.normal = c.normal;
  best.signed_distance = (p - c.point).dot(best.normal) >= 0.0 ? best.distance : -best.distance;
  return best;
}

}  // namespace argil
