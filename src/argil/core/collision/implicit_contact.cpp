#include "argil/core/collision/implicit_contact.hpp"

#include <algorithm>
#include <limits>
#include <set>

#include "argil/core/collision/detail/closest_search.hpp"
#include "argil/core/collision/detail/contact_regions.hpp"
#include "argil/core/collision/detail/patch_minimize.hpp"
#include "argil/core/collision/surface_contact.hpp"

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
  const ClosestFound found = closest_point_search(h, p, {.eps = request.tolerance}, best.counters);
  return closest_point_at(h.surface(), found.uv, p, best.counters);
}

}  // namespace argil
