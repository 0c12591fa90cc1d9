#include "argil/core/collision/detail/closest_search.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <tuple>
#include <vector>

#include "argil/core/collision/detail/patch_minimize.hpp"
#include "argil/core/collision/surface_contact.hpp"
#include "argil/core/geometry/triangle_distance.hpp"

namespace argil {

namespace {

PatchHints hints_of(const HierarchyNode& node) { return {&node.bound.corners, &node.patch}; }

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

/// A search entry. Equal lower bounds (0 for every node holding p) are
/// ordered by the node's place in the tree, not its id, so the answer does
/// not depend on the order in which earlier queries created nodes (ids change
/// when the pool is released). Blocks are entries -(id + 1), nodes id >= 0.
struct Entry {
  double lower;
  int level;  // -1 for blocks
  double u0, v0;
  int entry;
  bool operator>(const Entry& o) const {
    return std::tie(lower, level, u0, v0, entry) > std::tie(o.lower, o.level, o.u0, o.v0, o.entry);
  }
};
using EntryQueue = std::priority_queue<Entry, std::vector<Entry>, std::greater<>>;

Entry block_entry(double lower, int block) {
  return Entry{lower, -1, static_cast<double>(block), 0.0, -block - 1};
}
Entry node_entry(double lower, const HierarchyNode& n, int id) {
  return Entry{lower, n.level, n.rect.u0, n.rect.v0, id};
}

/// Lower bound of |p - S| over a node or block: its sphere, and (nodes) its
/// corner triangles less its flatness (exact point-triangle distances).
double node_lower(const Eigen::Vector3d& p, const PatchBound& b) {
  double lower = (p - b.center).norm() - b.radius;
  if (std::isfinite(b.flatness)) {
    const auto& c = b.corners;
    const double triangles = std::min((closest_point_on_triangle(p, c[0], c[1], c[3]) - p).norm(),
                                      (closest_point_on_triangle(p, c[0], c[3], c[2]) - p).norm());
    lower = std::max(lower, triangles - b.flatness);
  }
  return std::max(0.0, lower);
}

/// A node's rectangle with its sides on the domain's boundary pushed out to
/// infinity: a trim curve may run a little outside the domain (its points
/// are then evaluated at the clamped parameters, on that side).
ParamRect reach(const ParamRect& domain, const ParamRect& r) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  return {r.u0 <= domain.u0 ? -inf : r.u0, r.u1 >= domain.u1 ? inf : r.u1,
          r.v0 <= domain.v0 ? -inf : r.v0, r.v1 >= domain.v1 ? inf : r.v1};
}

bool is_leaf(const HierarchyNode& node, double eps) {
  return node.bound.flatness <= eps || node.bound.radius <= eps ||
         node.level >= SurfaceHierarchy::kMaxLevel;
}

/// The best-first search of closest_point().
class ClosestSearch {
 public:
  ClosestSearch(const SurfaceHierarchy& h, const Eigen::Vector3d& p,
                const ClosestSearchOptions& options, QueryCounters& counters)
      : h_(h),
        p_(p),
        f_(half_squared_distance_to(p)),
        eps_(options.eps),
        trim_(options.trim != nullptr && !options.trim->empty() ? options.trim : nullptr),
        domain_(domain_of(h.surface())),
        counters_(counters),
        best_distance_(options.bound),
        best_uv_(domain_of(h.surface()).lower()) {}

  ClosestFound run() {
    queue_.push(block_entry(node_lower(p_, h_.block(0, &counters_).bound), 0));
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
    return {best_uv_, found_ ? best_distance_ : std::numeric_limits<double>::infinity()};
  }

 private:
  /// A candidate point; outside the trim it is not material. The trim is
  /// asked only for points that would improve the best.
  void offer(const Eigen::Vector3d& x, const Eigen::Vector2d& uv) {
    const double d = (x - p_).norm();
    if (d < best_distance_ && (trim_ == nullptr || trim_->contains(uv))) {
      best_distance_ = d;
      best_uv_ = uv;
      found_ = true;
    }
  }

  void expand_block(int id) {
    const ElementBlock& block = h_.block(id, &counters_);
    if (block.element_node >= 0) {
      const HierarchyNode& n = h_.node(block.element_node, &counters_);
      queue_.push(node_entry(node_lower(p_, n.bound), n, block.element_node));
      return;
    }
    for (int c : block.children) {
      if (c < 0) continue;
      const double child_lower = node_lower(p_, h_.block(c, &counters_).bound);
      if (child_lower < best_distance_ - eps_) queue_.push(block_entry(child_lower, c));
    }
  }

  void visit_node(int id) {
    const HierarchyNode& node = h_.node(id, &counters_);
    // No material on the node: the boundary misses it and its centre is outside.
    if (trim_ != nullptr && !trim_->boundary_may_touch(reach(domain_, node.rect)) &&
        !trim_->contains(node.rect.centre())) {
      return;
    }
    // Patch corners lie on the surface: free upper bounds.
    for (int k = 0; k < 4; ++k)
      offer(node.bound.corners[static_cast<std::size_t>(k)], node.rect.corner(k));
    if (is_leaf(node, eps_)) {
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
        const double child_lower = node_lower(p_, child.bound);
        if (child_lower < best_distance_ - eps_) queue_.push(node_entry(child_lower, child, c));
      }
    }
  }

  const SurfaceHierarchy& h_;
  Eigen::Vector3d p_;
  PointFunction f_;
  double eps_;
  const TrimRegion* trim_;
  ParamRect domain_;
  QueryCounters& counters_;
  double best_distance_;
  Eigen::Vector2d best_uv_;
  bool found_ = false;
  EntryQueue queue_;
};

/// Most boundary pieces an edge-search leaf takes before it is split further.
constexpr std::size_t kLeafPieces = 8;

/// The best-first search of closest_edge_point(): the same node bounds, over
/// the nodes whose rectangle the trim boundary may touch; at a leaf every
/// piece touching it not yet searched is searched (TrimRegion::closest_on_piece).
class EdgeSearch {
 public:
  EdgeSearch(const SurfaceHierarchy& h, const TrimRegion& trim, const Eigen::Vector3d& p,
             double eps, QueryCounters& counters)
      : h_(h),
        trim_(trim),
        p_(p),
        eps_(eps),
        domain_(domain_of(h.surface())),
        counters_(counters),
        searched_(trim.piece_count(), 0) {}

  TrimEdgePoint run() {
    queue_.push(block_entry(node_lower(p_, h_.block(0, &counters_).bound), 0));
    while (!queue_.empty()) {
      const Entry top = queue_.top();
      queue_.pop();
      if (top.lower >= best_.distance - eps_) break;
      if (top.entry < 0) {
        expand_block(-top.entry - 1);
      } else {
        visit_node(top.entry);
      }
    }
    return best_;
  }

 private:
  void expand_block(int id) {
    const ElementBlock& block = h_.block(id, &counters_);
    if (block.element_node >= 0) {
      const HierarchyNode& n = h_.node(block.element_node, &counters_);
      queue_.push(node_entry(node_lower(p_, n.bound), n, block.element_node));
      return;
    }
    for (int c : block.children) {
      if (c < 0) continue;
      const double child_lower = node_lower(p_, h_.block(c, &counters_).bound);
      if (child_lower < best_.distance - eps_) queue_.push(block_entry(child_lower, c));
    }
  }

  void visit_node(int id) {
    const HierarchyNode& node = h_.node(id, &counters_);
    const ParamRect rect = reach(domain_, node.rect);
    if (is_leaf(node, eps_)) {
      pieces_.clear();
      // A flat node under many pieces (a plate with many holes) is split
      // further: smaller nodes bound the pieces far from p away.
      const std::size_t limit = node.level >= SurfaceHierarchy::kMaxLevel
                                    ? std::numeric_limits<std::size_t>::max()
                                    : kLeafPieces;
      if (trim_.pieces_touching(rect, pieces_, limit)) {
        if (pieces_.empty()) return;
        ++counters_.leaf_pairs;
        search_pieces(node);
        return;
      }
    } else if (!trim_.boundary_may_touch(rect)) {
      return;
    }
    // h_.child() may reallocate the node pool: `node` is not used after this.
    for (int hu = 0; hu < 2; ++hu) {
      for (int hv = 0; hv < 2; ++hv) {
        const int c = h_.child(id, hu, hv);
        const HierarchyNode& child = h_.node(c, &counters_);
        const double child_lower = node_lower(p_, child.bound);
        if (child_lower < best_.distance - eps_) queue_.push(node_entry(child_lower, child, c));
      }
    }
  }

  /// A lower bound of |p - S| over the part of `piece` inside the flat leaf
  /// `node`: S is within the leaf's flatness of the bilinear interpolation L
  /// of its corners, and L maps the piece's box (clipped to the leaf) into
  /// the box of the images of its corners.
  double piece_lower(const HierarchyNode& node, const TrimRegion::Piece& piece) const {
    const ParamRect& r = node.rect;
    const auto& c = node.bound.corners;
    const double u0 = std::clamp(piece.lo.x(), r.u0, r.u1),
                 u1 = std::clamp(piece.hi.x(), r.u0, r.u1);
    const double v0 = std::clamp(piece.lo.y(), r.v0, r.v1),
                 v1 = std::clamp(piece.hi.y(), r.v0, r.v1);
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector3d hi = -lo;
    for (const double u : {u0, u1}) {
      for (const double v : {v0, v1}) {
        const double s = r.width() > 0.0 ? (u - r.u0) / r.width() : 0.0;
        const double t = r.height() > 0.0 ? (v - r.v0) / r.height() : 0.0;
        const Eigen::Vector3d x =
            (1 - s) * (1 - t) * c[0] + s * (1 - t) * c[1] + (1 - s) * t * c[2] + s * t * c[3];
        lo = lo.cwiseMin(x);
        hi = hi.cwiseMax(x);
      }
    }
    const Eigen::Vector3d gap = (lo - p_).cwiseMax(p_ - hi).cwiseMax(0.0);
    return gap.norm() - node.bound.flatness;
  }

  /// The pieces touching a flat leaf (in pieces_), nearest bound first, each
  /// searched once (on its whole length) unless its part here cannot beat the best.
  void search_pieces(const HierarchyNode& node) {
    candidates_.clear();
    for (const int k : pieces_) {
      if (searched_[static_cast<std::size_t>(k)] != 0) continue;
      candidates_.emplace_back(piece_lower(node, trim_.piece(k)), k);
    }
    std::sort(candidates_.begin(), candidates_.end());
    for (const auto& [lower, k] : candidates_) {
      if (lower >= best_.distance - eps_) break;
      searched_[static_cast<std::size_t>(k)] = 1;
      const TrimEdgePoint e = trim_.closest_on_piece(k, h_.surface(), p_);
      if (e.distance < best_.distance) best_ = e;
    }
  }

  const SurfaceHierarchy& h_;
  const TrimRegion& trim_;
  Eigen::Vector3d p_;
  double eps_;
  ParamRect domain_;
  QueryCounters& counters_;
  TrimEdgePoint best_;
  std::vector<char> searched_;  // per piece
  std::vector<int> pieces_;
  std::vector<std::pair<double, int>> candidates_;
  EntryQueue queue_;
};

}  // namespace

ClosestFound closest_point_search(const SurfaceHierarchy& h, const Eigen::Vector3d& p,
                                  const ClosestSearchOptions& options, QueryCounters& counters) {
  return ClosestSearch(h, p, options, counters).run();
}

TrimEdgePoint closest_edge_search(const SurfaceHierarchy& h, const TrimRegion& trim,
                                  const Eigen::Vector3d& p, double eps, QueryCounters& counters) {
  return EdgeSearch(h, trim, p, eps, counters).run();
}

ClosestPoint closest_point_at(const BSplineSurface& surface, const Eigen::Vector2d& uv,
                              const Eigen::Vector3d& p, const QueryCounters& counters) {
  ClosestPoint out;
  const SurfaceDerivatives d = evaluate_derivatives(surface, uv[0], uv[1], 1);
  const Contact c = contact_at(surface, uv, d, 0.0);
  out.uv = uv;
  out.point = c.point;
  out.distance = (p - c.point).norm();
  out.normal = c.normal;
  out.signed_distance = (p - c.point).dot(out.normal) >= 0.0 ? out.distance : -out.distance;
  out.counters = counters;
  return out;
}

}  // namespace argil
