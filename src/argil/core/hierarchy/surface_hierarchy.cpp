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
  // Which poles changed, as a 2D prefix count so an element's support (a
  // (p + 1) x (q + 1) block of poles) is tested in O(1).
  const int nu = surface_.count(Direction::u), nv = surface_.count(Direction::v);
  std::vector<int> changed(static_cast<std::size_t>(nu + 1) * static_cast<std::size_t>(nv + 1), 0);
  const auto at = [&](int i, int j) -> int& {
    return changed[static_cast<std::size_t>(i) * static_cast<std::size_t>(nv + 1) +
                   static_cast<std::size_t>(j)];
  };
  bool any = false;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const Eigen::Index k = surface_.pole_index(i, j);
      const bool moved = points.row(k) != surface_.control_points.row(k) ||
                         (weights.size() > 0 && weights[k] != surface_.weights[k]);
      any = any || moved;
      at(i + 1, j + 1) = (moved ? 1 : 0) + at(i, j + 1) + at(i + 1, j) - at(i, j);
    }
  stale_elements_ = 0;
  if (!any) return;  // nothing moved: every bound still holds
  surface_.control_points = points;
  if (weights.size() > 0) surface_.weights = weights;
  ++version_;
  const auto moved_in = [&](int i0, int i1, int j0, int j1) {  // poles [i0, i1] x [j0, j1]
    return at(i1 + 1, j1 + 1) - at(i0, j1 + 1) - at(i1 + 1, j0) + at(i0, j0) > 0;
  };
  const int p = surface_.degree[0], q = surface_.degree[1];
  const auto& su = ops_.u->extraction().spans;
  const auto& sv = ops_.v->extraction().spans;
  for (std::size_t eu = 0; eu < su.size(); ++eu)
    for (std::size_t ev = 0; ev < sv.size(); ++ev)
      if (moved_in(su[eu] - p, su[eu], sv[ev] - q, sv[ev])) {
        element_version_[eu * sv.size() + ev] = version_;
        ++stale_elements_;
      }
  for (ElementBlock& b : blocks_)
    if (b.fresh) {
      const int i0 = su[static_cast<std::size_t>(b.eu0)] - p;
      const int i1 = su[static_cast<std::size_t>(b.eu1 - 1)];
      const int j0 = sv[static_cast<std::size_t>(b.ev0)] - q;
      const int j1 = sv[static_cast<std::size_t>(b.ev1 - 1)];
      b.fresh = !moved_in(i0, i1, j0, j1);
    }
  if (nodes_.size() > node_budget_) release_nodes();
}

void SurfaceHierarchy::release_nodes() {
  // Roots are the first nodes (build() creates them before any child).
  nodes_.resize(roots_.size());
  for (HierarchyNode& root : nodes_) root.children = {-1, -1, -1, -1};
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
    refresh(self.parent, counters);  // creates no nodes, so `self` stays valid
    const HierarchyNode& parent = nodes_[static_cast<std::size_t>(self.parent)];
    self.patch = subdivide(parent.patch, ops_.u->subdivision(), ops_.v->subdivision(),
                           {self.half_u, self.half_v});
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
  nodes_.push_back(std::move(c));  // may reallocate: no references held across this
  nodes_[static_cast<std::size_t>(id)].children[static_cast<std::size_t>(slot)] = index;
  return index;
}

}  // namespace argil
