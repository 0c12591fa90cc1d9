#pragma once
// The conservative, lazy hierarchy (docs/collision.md): Bezier sub-patch nodes
// bounded from their control points, created only where queries reach and
// refreshed only where queries reach after the control points change.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "argil/core/base/chunked_vector.hpp"
#include "argil/core/base/status.hpp"
#include "argil/core/geometry/bezier.hpp"
#include "argil/core/geometry/bspline_surface.hpp"
#include "argil/core/geometry/param_rect.hpp"
#include "argil/core/hierarchy/patch_bound.hpp"
#include "argil/core/operators/surface_operators.hpp"

namespace argil {

/// One node: the Bezier sub-patch over `rect` of element
/// (element_u, element_v) at `level` (each level halves both directions).
struct HierarchyNode {
  int element_u = 0;
  int element_v = 0;
  int level = 0;
  int parent = -1;
  int half_u = 0;  // which half of the parent, in u and v
  int half_v = 0;
  ParamRect rect;
  std::array<int, 4> children{-1, -1, -1, -1};  // index half_u * 2 + half_v
  BezierPatch patch;
  PatchBound bound;
  std::uint64_t version = 0;  // control-point version the patch was built from
};

/// A block of Bezier elements [eu0, eu1) x [ev0, ev1) above the element roots,
/// so a query reaches the few elements near a tool in O(log) sphere tests
/// instead of testing every element. Its bound encloses the B-spline control
/// points acting on those elements (convex hull property of the B-spline).
struct ElementBlock {
  int eu0 = 0, eu1 = 0, ev0 = 0, ev1 = 0;
  std::array<int, 4> children{-1, -1, -1, -1};  // sub-blocks; -1 where a range cannot split
  int element_node = -1;  // the element's root node when the block is one element
  PatchBound bound;       // centre, radius and box only (flatness is not defined)
  bool fresh = false;     // the bound holds the current control points
};

/// Work a query did, for benchmarks and the speed/accuracy trade.
struct QueryCounters {
  long nodes_visited = 0;    // node bounds read (surface pairs: each node once per query)
  long nodes_refreshed = 0;  // nodes whose Bezier net was (re)computed
  long leaf_pairs = 0;       // leaves (or leaf pairs) examined exactly
  long triangle_tests = 0;   // triangle-triangle or triangle-tool tests
};

/// Owns a copy of the surface's control points (the per-frame state), shares
/// its operators, and grows nodes on demand. The nodes and blocks are a cache
/// over the control points: queries take `const SurfaceHierarchy&` and fill
/// this mutable lazy cache through it, which changes no answer. So const does
/// not mean shareable: do not share one object across threads (not even for
/// const queries); give each thread its own copy. Only setting control points
/// and the node budget need non-const access.
class SurfaceHierarchy {
 public:
  /// Validates the surface and fetches its operators from `cache`.
  static Result<SurfaceHierarchy> build(const BSplineSurface& surface, OperatorCache& cache);

  const BSplineSurface& surface() const { return surface_; }
  const SurfaceOperators& operators() const { return ops_; }
  std::uint64_t version() const { return version_; }

  /// New control points (and weights for a rational surface), same structure:
  /// O(n) copy and compare. Only the elements whose support holds a control
  /// point that changed (bit for bit) go stale, with their nodes and the
  /// blocks over them; they are refreshed when next reached. The rest keep
  /// their bounds: a body solved only near the tool, or at rest, refreshes
  /// nothing elsewhere.
  void set_control_points(const ControlNet& points, const Eigen::VectorXd& weights = {});
  /// The same for a net that differs from the current one only in the poles
  /// (i, j), i0 <= i < i1 and j0 <= j < j1 (the rest are not read): the cost
  /// follows the box, not the net (a body solved in a window near the tool).
  /// The weights do not change.
  void set_control_points_in(const ControlNet& points, int i0, int i1, int j0, int j1);
  /// Elements (Bezier patches) the last set_control_points made stale.
  int stale_elements() const { return stale_elements_; }

  /// One node per Bezier element: the hierarchy's roots.
  const std::vector<int>& roots() const { return roots_; }
  /// The block tree over the elements (built with the structure; bounds lazy).
  /// Block 0 covers every element: its bound is the broad-phase bound of the surface.
  const ElementBlock& block(int id, QueryCounters* counters = nullptr) const;
  /// The node with fresh bounds (refreshing its ancestors first if needed).
  const HierarchyNode& node(int id, QueryCounters* counters = nullptr) const;
  /// Index of child (half_u, half_v) of `id`, created on first use.
  /// Creating a node never moves the others: references from node() stay
  /// valid until the nodes are released.
  int child(int id, int half_u, int half_v) const;

  /// Number of nodes created so far (for tests and memory accounting).
  std::size_t node_count() const { return nodes_.size(); }
  /// Memory bound: when set_control_points finds more nodes below the roots
  /// (one per element) than this, it drops them all (queries grow them again where they
  /// reach). This costs allocations and refreshes, never results: a query gives the same answer
  /// on a collapsed hierarchy as on a grown one.
  void set_node_budget(std::size_t nodes) { node_budget_ = nodes; }
  std::size_t node_budget() const { return node_budget_; }
  /// Drops every node below the roots now.
  void release_nodes();
  /// Drops every node below the roots when there are more than the budget
  /// (set_control_points does this; a hierarchy that is never re-posed, such
  /// as a rigid tool placed per query, calls it itself).
  void keep_within_node_budget();
  /// Deepest level a query may split to; below it a node is treated as a leaf
  /// whatever its flatness (guards against endless refinement at degeneracies).
  static constexpr int kMaxLevel = 24;

 private:
  SurfaceHierarchy() = default;
  void refresh(int id, QueryCounters* counters) const;
  int build_block(int eu0, int eu1, int ev0, int ev1);
  /// Marks stale the blocks under `id` whose elements hold one in
  /// [eu0, eu1) x [ev0, ev1) that `stale` says changed.
  template <class Stale>
  void stale_blocks(int id, int eu0, int eu1, int ev0, int ev1, const Stale& stale);

  BSplineSurface surface_;
  SurfaceOperators ops_;
  std::uint64_t version_ = 1;
  /// Per element (u-major): the version its control points last changed at. A
  /// node is fresh while its version is at least its element's.
  std::vector<std::uint64_t> element_version_;
  int stale_elements_ = 0;
  // Chunked: growing the pool in a query never copies it (see ChunkedVector).
  // 16 nodes a chunk (4.6 KB): a scene of a thousand small faces, each with a
  // partly used last chunk, wastes under 5 MB.
  mutable ChunkedVector<HierarchyNode, 16> nodes_;
  std::vector<int> roots_;
  mutable std::vector<ElementBlock> blocks_;
  std::size_t node_budget_ = std::size_t{1} << 15;  // about 25 MB of bicubic nodes
};

}  // namespace argil
