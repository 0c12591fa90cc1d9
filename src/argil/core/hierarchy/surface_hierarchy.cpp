#include "argil/core/hierarchy/surface_hierarchy.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace argil {

Result<SurfaceHierarchy> SurfaceHierarchy::build(const BSplineSurface& surface,
                                                 OperatorCache& cache) {
  Result<SurfaceOperators> ops = surface_operators(surface, cache);
  if (!ops.ok()) return ops.status();
  SurfaceHierarchy h;
  h.surface_ = surface;
  h.ops_ = ops.value();
  const BezierExtraction& xu = h.ops_.u->extraction();
  const BezierExtraction& xv = h.ops_.v->extraction();
  for (std::size_t eu = 0; eu < xu.spans.size(); ++eu) {
    for (std::size_t ev = 0; ev < xv.spans.size(); ++ev) {
      HierarchyNode n;
      n.element_u = static_cast<int>(eu);
      n.element_v = static_cast<int>(ev);
      n.rect = {surface.knots[0][xu.spans[eu]], surface.knots[0][xu.spans[eu] + 1],
                surface.knots[1][xv.spans[ev]], surface.knots[1][xv.spans[ev] + 1]};
      n.version = 0;  // stale: built on first visit
      h.roots_.push_back(static_cast<int>(h.nodes_.size()));
      h.nodes_.push_back(std::move(n));
    }
  }
  h.element_version_.assign(h.roots_.size(), h.version_);
  h.build_block(0, static_cast<int>(xu.spans.size()), 0, static_cast<int>(xv.spans.size()));
  return h;
}

int SurfaceHierarchy::build_block(int eu0, int eu1, int ev0, int ev1) {
  const int id = static_cast<int>(blocks_.size());
  ElementBlock fresh;
  fresh.eu0 = eu0;
  fresh.eu1 = eu1;
  fresh.ev0 = ev0;
  fresh.ev1 = ev1;
  blocks_.push_back(fresh);
  const int elements_v = ops_.v->element_count();
  if (eu1 - eu0 == 1 && ev1 - ev0 == 1) {
    blocks_[static_cast<std::size_t>(id)].element_node =
        roots_[static_cast<std::size_t>(eu0 * elements_v + ev0)];
    return id;
  }
  // Halve every range that has more than one element.
  const int mu = eu1 - eu0 > 1 ? (eu0 + eu1) / 2 : eu1;
  const int mv = ev1 - ev0 > 1 ? (ev0 + ev1) / 2 : ev1;
  const int u_ranges[2][2] = {{eu0, mu}, {mu, eu1}};
  const int v_ranges[2][2] = {{ev0, mv}, {mv, ev1}};
  for (int hu = 0; hu < 2; ++hu) {
    for (int hv = 0; hv < 2; ++hv) {
      const int* ru = u_ranges[hu];
      const int* rv = v_ranges[hv];
      if (ru[0] >= ru[1] || rv[0] >= rv[1]) continue;
      const int c = build_block(ru[0], ru[1], rv[0], rv[1]);
      blocks_[static_cast<std::size_t>(id)].children[static_cast<std::size_t>(hu * 2 + hv)] = c;
    }
  }
  return id;
}

const ElementBlock& SurfaceHierarchy::block(int id, QueryCounters* counters) const {
  ElementBlock& b = blocks_[static_cast<std::size_t>(id)];
  if (counters) ++counters->nodes_visited;
  if (b.fresh) return b;
  if (b.element_node < 0) {
    // The union of the sub-blocks' boxes: the box of the same poles, and a
    // local change refreshes one path of blocks, not the whole net.
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector3d hi = -lo;
    for (const int c : b.children) {
      if (c < 0) continue;
      const Box3& box = block(c, counters).bound.box;
      lo = lo.cwiseMin(box.min);
      hi = hi.cwiseMax(box.max);
    }
    ElementBlock& self = blocks_[static_cast<std::size_t>(id)];  // `b` still valid: no growth
    self.bound.box = {lo, hi};
    self.bound.center = 0.5 * (lo + hi);
    self.bound.radius = 0.5 * (hi - lo).norm();
    self.bound.flatness = std::numeric_limits<double>::infinity();
    self.fresh = true;
    if (counters) ++counters->nodes_refreshed;
    return self;
  }
  const int p = surface_.degree[0];
  const int q = surface_.degree[1];
  const int i0 = ops_.u->extraction().spans[static_cast<std::size_t>(b.eu0)] - p;
  const int i1 = ops_.u->extraction().spans[static_cast<std::size_t>(b.eu1 - 1)];
  const int j0 = ops_.v->extraction().spans[static_cast<std::size_t>(b.ev0)] - q;
  const int j1 = ops_.v->extraction().spans[static_cast<std::size_t>(b.ev1 - 1)];
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (int i = i0; i <= i1; ++i) {
    for (int j = j0; j <= j1; ++j) {
      const Eigen::Vector3d x = surface_.control_points.row(surface_.pole_index(i, j)).transpose();
      lo = lo.cwiseMin(x);
      hi = hi.cwiseMax(x);
    }
  }
  // One pass over the poles: the box, and the sphere around it (looser than
  // the tightest, but blocks are refreshed every tick on a deforming surface).
  b.bound.box = {lo, hi};
  b.bound.center = 0.5 * (lo + hi);
  b.bound.radius = 0.5 * (hi - lo).norm();
  b.bound.flatness = std::numeric_limits<double>::infinity();
  b.fresh = true;
  if (counters) ++counters->nodes_refreshed;
  return b;
}

void SurfaceHierarchy::set_control_points(const ControlNet& points,
                                          const Eigen::VectorXd& weights) {
  assert(points.rows() == surface_.control_points.rows());
  assert(weights.size() == 0 || weights.size() == surface_.weights.size());
  if (weights.size() > 0 && weights != surface_.weights) {
    // A weight change goes through the whole net (rare: imports, tests).
    surface_.weights = weights;
    surface_.control_points = points;
    ++version_;
    element_version_.assign(element_version_.size(), version_);
    stale_elements_ = static_cast<int>(element_version_.size());
    for (ElementBlock& b : blocks_) b.fresh = false;
    keep_within_node_budget();
    return;
  }
  set_control_points_in(points, 0, surface_.count(Direction::u), 0, surface_.count(Direction::v));
}

void SurfaceHierarchy::set_control_points_in(const ControlNet& points, int i0, int i1, int j0,
                                             int j1) {
  assert(points.rows() == surface_.control_points.rows());
  const int nu = surface_.count(Direction::u), nv = surface_.count(Direction::v);
  i0 = std::max(i0, 0), i1 = std::min(i1, nu), j0 = std::max(j0, 0), j1 = std::min(j1, nv);
  stale_elements_ = 0;
  if (i0 >= i1 || j0 >= j1) return;
  // Which poles of the box changed, as a 2D prefix count so an element's
  // support (a (p + 1) x (q + 1) block of poles) is tested in O(1).
  const int wu = i1 - i0, wv = j1 - j0;
  std::vector<int> changed(static_cast<std::size_t>(wu + 1) * static_cast<std::size_t>(wv + 1), 0);
  const auto at = [&](int i, int j) -> int& {  // box-relative
    return changed[static_cast<std::size_t>(i) * static_cast<std::size_t>(wv + 1) +
                   static_cast<std::size_t>(j)];
  };
  bool any = false;
  for (int i = 0; i < wu; ++i)
    for (int j = 0; j < wv; ++j) {
      const Eigen::Index k = surface_.pole_index(i0 + i, j0 + j);
      const bool moved = points.row(k) != surface_.control_points.row(k);
      if (moved) surface_.control_points.row(k) = points.row(k);
      any = any || moved;
      at(i + 1, j + 1) = (moved ? 1 : 0) + at(i, j + 1) + at(i + 1, j) - at(i, j);
    }
  if (!any) return;  // nothing moved: every bound still holds
  ++version_;
  // Whether a pole in [a0, a1] x [b0, b1] (inclusive, net indices) moved.
  const auto moved_in = [&](int a0, int a1, int b0, int b1) {
    a0 = std::max(a0, i0) - i0, a1 = std::min(a1, i1 - 1) - i0;
    b0 = std::max(b0, j0) - j0, b1 = std::min(b1, j1 - 1) - j0;
    if (a0 > a1 || b0 > b1) return false;
    return at(a1 + 1, b1 + 1) - at(a0, b1 + 1) - at(a1 + 1, b0) + at(a0, b0) > 0;
  };
  const int p = surface_.degree[0], q = surface_.degree[1];
  const auto& su = ops_.u->extraction().spans;
  const auto& sv = ops_.v->extraction().spans;
  // The elements whose support (poles span - p .. span) meets the box.
  const auto elements = [](const std::vector<int>& spans, int degree, int first, int last) {
    const auto lo = std::lower_bound(spans.begin(), spans.end(), first);
    const auto hi = std::upper_bound(spans.begin(), spans.end(), last + degree);
    return std::pair<int, int>{static_cast<int>(lo - spans.begin()),
                               static_cast<int>(hi - spans.begin())};
  };
  const auto [eu0, eu1] = elements(su, p, i0, i1 - 1);
  const auto [ev0, ev1] = elements(sv, q, j0, j1 - 1);
  for (int eu = eu0; eu < eu1; ++eu)
    for (int ev = ev0; ev < ev1; ++ev) {
      const std::size_t e = static_cast<std::size_t>(eu) * sv.size() + static_cast<std::size_t>(ev);
      if (moved_in(su[static_cast<std::size_t>(eu)] - p, su[static_cast<std::size_t>(eu)],
                   sv[static_cast<std::size_t>(ev)] - q, sv[static_cast<std::size_t>(ev)])) {
        element_version_[e] = version_;
        ++stale_elements_;
      }
    }
  stale_blocks(0, eu0, eu1, ev0, ev1, [&](int eu, int ev) {
    return element_version_[static_cast<std::size_t>(eu) * sv.size() +
                            static_cast<std::size_t>(ev)] == version_;
  });
  keep_within_node_budget();
}

void SurfaceHierarchy::keep_within_node_budget() {
  if (nodes_.size() > roots_.size() + node_budget_) release_nodes();
}

template <class Stale>
void SurfaceHierarchy::stale_blocks(int id, int eu0, int eu1, int ev0, int ev1,
                                    const Stale& stale) {
  ElementBlock& b = blocks_[static_cast<std::size_t>(id)];
  const int u0 = std::max(b.eu0, eu0), u1 = std::min(b.eu1, eu1);
  const int v0 = std::max(b.ev0, ev0), v1 = std::min(b.ev1, ev1);
  if (u0 >= u1 || v0 >= v1) return;
  // A stale block's sub-blocks may be fresh (a block's bound is computed from
  // its sub-blocks'), so the walk goes on below it.
  bool any = false;
  if (b.element_node >= 0) {
    any = stale(b.eu0, b.ev0);
  } else {
    for (const int c : b.children) {
      if (c < 0) continue;
      stale_blocks(c, eu0, eu1, ev0, ev1, stale);
      any = any || !blocks_[static_cast<std::size_t>(c)].fresh;
    }
  }
  if (any) b.fresh = false;
}

void SurfaceHierarchy::release_nodes() {
  // Roots are the first nodes (build() creates them before any child).
  nodes_.truncate(roots_.size());
  for (std::size_t r = 0; r < nodes_.size(); ++r) nodes_[r].children = {-1, -1, -1, -1};
}

void SurfaceHierarchy::refresh(int id, QueryCounters* counters) const {
  HierarchyNode& self = nodes_[static_cast<std::size_t>(id)];
  const std::size_t element =
      static_cast<std::size_t>(self.element_u) * ops_.v->extraction().spans.size() +
      static_cast<std::size_t>(self.element_v);
  if (self.version >= element_version_[element]) return;
  if (self.parent < 0) {
    self.patch = bezier_patch(surface_, ops_, self.element_u, self.element_v);
  } else {
    refresh(self.parent, counters);
    const HierarchyNode& parent = nodes_[static_cast<std::size_t>(self.parent)];
    subdivide_into(parent.patch, ops_.u->subdivision(), ops_.v->subdivision(),
                   {self.half_u, self.half_v}, self.patch);
  }
  self.bound = bound_patch(self.patch);
  self.version = version_;
  if (counters) ++counters->nodes_refreshed;
}

const HierarchyNode& SurfaceHierarchy::node(int id, QueryCounters* counters) const {
  refresh(id, counters);
  if (counters) ++counters->nodes_visited;
  return nodes_[static_cast<std::size_t>(id)];
}

int SurfaceHierarchy::child(int id, int half_u, int half_v) const {
  const int slot = half_u * 2 + half_v;
  const int existing =
      nodes_[static_cast<std::size_t>(id)].children[static_cast<std::size_t>(slot)];
  if (existing >= 0) return existing;
  const HierarchyNode& parent = nodes_[static_cast<std::size_t>(id)];
  HierarchyNode c;
  c.element_u = parent.element_u;
  c.element_v = parent.element_v;
  c.level = parent.level + 1;
  c.parent = id;
  c.half_u = half_u;
  c.half_v = half_v;
  c.rect = parent.rect.quarter(half_u, half_v);
  c.version = 0;
  const int index = static_cast<int>(nodes_.size());
  nodes_.push_back(std::move(c));
  nodes_[static_cast<std::size_t>(id)].children[static_cast<std::size_t>(slot)] = index;
  return index;
}

}  // namespace argil
