#include "argil/core/haptic/sphere_proxy.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

namespace argil {

namespace {

/// True when the closest point lies on the domain boundary or a trimmed
/// edge: there it may be reached from either side without crossing the surface.
bool on_boundary(const BSplineSurface& s, const ClosestPoint& cp) {
  const Eigen::Vector2d& uv = cp.uv;
  return cp.on_edge || uv.x() <= s.domain_start(Direction::u) ||
         uv.x() >= s.domain_end(Direction::u) || uv.y() <= s.domain_start(Direction::v) ||
         uv.y() >= s.domain_end(Direction::v);
}

}  // namespace

Eigen::Vector3d push_apart(const std::vector<PushConstraint>& pushes) {
  // min |x|^2 subject to n_k . x >= d_k. In 3D at most three pushes are active
  // at the optimum, so try every set of one to three independent pushes as
  // equalities (x = N lambda, N^T N lambda = d, lambda >= 0) and keep the
  // shortest x that satisfies them all. A handful of surfaces touch a proxy,
  // so the enumeration is cheap and has no degenerate cases to get wrong.
  const auto feasible = [&](const Eigen::Vector3d& x) {
    for (const PushConstraint& p : pushes)
      if (p.normal.dot(x) < p.depth - 1e-12 * std::max(1.0, std::abs(p.depth))) return false;
    return true;
  };
  const std::size_t n = pushes.size();
  Eigen::Vector3d best = Eigen::Vector3d::Zero();
  if (feasible(best)) return best;
  double best_norm = std::numeric_limits<double>::infinity();
  const auto consider = [&](std::initializer_list<std::size_t> set) {
    const Eigen::Index m = static_cast<Eigen::Index>(set.size());
    Eigen::MatrixXd normals(3, m);
    Eigen::VectorXd depth(m);
    Eigen::Index a = 0;
    for (const std::size_t k : set) {
      normals.col(a) = pushes[k].normal;
      depth[a++] = pushes[k].depth;
    }
    const Eigen::MatrixXd gram = normals.transpose() * normals;
    const Eigen::LDLT<Eigen::MatrixXd> ldlt(gram);
    // Dependent normals (a flat seam) make a singular set; a smaller set covers it.
    if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().minCoeff() > 1e-12)) return;
    const Eigen::VectorXd lambda = ldlt.solve(depth);
    if (!(lambda.minCoeff() >= 0.0)) return;
    const Eigen::Vector3d x = normals * lambda;
    if (x.norm() < best_norm && feasible(x)) {
      best = x;
      best_norm = x.norm();
    }
  };
  for (std::size_t i = 0; i < n; ++i) {
    consider({i});
    for (std::size_t j = i + 1; j < n; ++j) {
      consider({i, j});
      for (std::size_t k = j + 1; k < n; ++k) consider({i, j, k});
    }
  }
  if (std::isfinite(best_norm)) return best;
  // No set satisfies every push (opposed pushes: the proxy is squeezed
  // between surfaces): take the deepest push alone.
  const auto deepest = std::max_element(
      pushes.begin(), pushes.end(),
      [](const PushConstraint& x, const PushConstraint& y) { return x.depth < y.depth; });
  return deepest->depth * deepest->normal;
}

int& SphereProxy::side(std::size_t index) {
  if (sides_.size() <= index) sides_.resize(index + 1, 0);
  return sides_[index];
}

SphereProxy::Seen& SphereProxy::seen(std::size_t index) {
  if (seen_.size() <= index) seen_.resize(index + 1);
  return seen_[index];
}

void SphereProxy::set_surface_motion(std::vector<double> motion, std::vector<double> travel) {
  ++epoch_;
  if (travel.empty()) travel = motion;
  if (surface_path_.size() < travel.size()) surface_path_.resize(travel.size(), 0.0);
  for (std::size_t b = 0; b < travel.size(); ++b) surface_path_[b] += travel[b];
  motion_ = std::move(motion);
}

void SphereProxy::forget_side(std::size_t index) {
  if (index < sides_.size()) sides_[index] = 0;
  if (index < seen_.size()) seen_[index] = {};
}

void SphereProxy::walk_to(const Eigen::Vector3d& centre) {
  if (walked_) path_ += (centre - last_centre_).norm();
  walked_ = true;
  last_centre_ = centre;
}

SphereProxy::Stance SphereProxy::stance(const TrimmedSurface& surface, std::size_t index) const {
  return {surface.hierarchy->version(), epoch_,
          index < surface_path_.size() ? surface_path_[index] : 0.0};
}

double SphereProxy::surface_moved(const TrimmedSurface& surface, std::size_t index,
                                  const Stance& then) const {
  const Stance now = stance(surface, index);
  if (now.version == then.version) return 0.0;
  const double told = now.surface_path - then.surface_path;
  // Changed, and no motion told for it since (not listed, or told 0: a
  // sleeping body a joint nudged): unknown.
  if (now.epoch == then.epoch || !(told > 0.0)) return std::numeric_limits<double>::infinity();
  return told;
}

int SphereProxy::side_where_passed(const TrimmedSurface& surface, std::size_t index,
                                   const Pass& pass) {
  const double tiny = 1e-3 * eps_;
  if (!(pass.clear - surface_moved(surface, index, pass.stance) > tiny)) return 0;
  const ClosestPoint there = closest_point(surface, pass.at, {.tolerance = 0.25 * eps_});
  ++queries_;
  if (!there.status.ok() || !(std::abs(there.signed_distance) > tiny)) return 0;
  return there.signed_distance < 0.0 ? -1 : 1;
}

SphereProxy::DistanceBounds SphereProxy::distance_bounds(const TrimmedSurface& surface,
                                                         std::size_t index) {
  const Seen& s = seen(index);
  if (s.hierarchy != surface.hierarchy || s.trim != surface.trim) return {};
  // The distance found is within eps/4 of the true one; since, the centre
  // went no farther than its path and the surface no farther than it moved.
  const double since = (path_ - s.path) + surface_moved(surface, index, s.stance);
  return {s.found.distance - 0.25 * eps_ - since, s.found.distance + since};
}

ClosestPoint SphereProxy::closest(const TrimmedSurface& surface, std::size_t index,
                                  const Eigen::Vector3d& centre, bool record) {
  Seen& s = seen(index);
  if (s.hierarchy == surface.hierarchy && s.trim == surface.trim &&
      s.stance.version == surface.hierarchy->version() && s.centre == centre)
    return s.found;
  ClosestPoint cp = closest_point(surface, centre, {.tolerance = 0.25 * eps_});
  ++queries_;
  if (record && cp.status.ok()) {
    s = {.hierarchy = surface.hierarchy,
         .trim = surface.trim,
         .stance = stance(surface, index),
         .path = path_,
         .clear = false,
         .passed = std::nullopt,
         .centre = centre,
         .found = cp};
  }
  return cp;
}

SphereProxy::Push SphereProxy::push_out(const TrimmedSurface& surface, std::size_t index,
                                        const Eigen::Vector3d& c, double travel) {
  const double tiny = 1e-3 * eps_;  // below it the sign of a distance is noise
  walk_to(c);
  // No point of the surface can have come within reach since it was seen:
  // no push, and the centre cannot have crossed it.
  const double clear = distance_bounds(surface, index).at_least;
  if (Seen& record = seen(index); record.clear && clear > radius_ + tiny) {
    record.passed = Pass{c, clear, stance(surface, index)};
    return {Status::success(), c, false};
  }
  const std::optional<Pass> passed = seen(index).passed;
  ClosestPoint cp = closest(surface, index, c, true);
  if (!cp.status.ok()) return {std::move(cp.status), c, false};
  seen(index).clear = false;  // until found clear below
  seen(index).passed.reset();
  const bool boundary = on_boundary(surface.hierarchy->surface(), cp);
  int& s = side(index);
  // Passed by, the side was not followed round an edge (below). If the
  // surface still cannot have met the centre since it was seen, the side is
  // the sign here; else it is the sign where it was last passed (farther
  // than the radius then, and nothing crossed on the way there), and the
  // last step, from there to here, is judged below as any other.
  if (passed) {
    if (clear > 0.0) {
      if (std::abs(cp.signed_distance) > tiny) s = cp.signed_distance < 0.0 ? -1 : 1;
    } else if (const int there = side_where_passed(surface, index, *passed); there != 0) {
      s = there;
    }
  }
  if (s == 0) s = cp.signed_distance < 0.0 ? -1 : 1;
  bool crossed = s * cp.signed_distance < -tiny && !boundary;
  // A crossing leaves the centre behind the surface by at most what the two
  // travelled towards each other since the centre was found clear (its own
  // travel and the surface's motion, set_surface_motion) less the radius it
  // then stood in front (within eps/4), plus eps. Farther behind, the side
  // read is that of a face turning over within reach (round a pinched tip, a
  // fold) or of an edge the centre slid round while touching it: read
  // afresh. Taken as a crossing, the centre was thrown through, two radii
  // and more, tick after tick, and the faces it landed in crumpled.
  const double moved = index < motion_.size() ? motion_[index] : 0.0;
  if (crossed && cp.distance > std::max(0.0, travel + moved - radius_ + 0.25 * eps_) + eps_) {
    s = -s;
    crossed = false;
  }
  if (!crossed && cp.distance >= radius_) {
    if (cp.distance > radius_ + tiny && std::abs(cp.signed_distance) > tiny && boundary)
      s = cp.signed_distance < 0.0 ? -1 : 1;  // went round the edge
    seen(index).clear = true;
    return {Status::success(), c, false};
  }
  Eigen::Vector3d direction = s * cp.normal;
  if (!crossed && cp.distance > tiny) direction = (c - cp.point) / cp.distance;
  // A degenerate normal and no offset: nowhere to push.
  if (direction.squaredNorm() == 0.0) return {Status::success(), c, false};
  // A point tool stays a hair off the surface so its side stays readable.
  return {Status::success(), cp.point + direction * std::max(radius_, 2.0 * tiny), true};
}

SphereMove SphereProxy::project(const std::vector<TrimmedSurface>& surfaces,
                                const Eigen::Vector3d& start, double travel) {
  // Every surface's push is taken from the same centre and the pushes are
  // combined by the smallest move that satisfies them all (push_apart). Pushing
  // out of one surface after another instead zigzags in a groove or at a seam
  // and stops on a different side each tick: the proxy flip-flops.
  Eigen::Vector3d centre = start;
  std::vector<PushConstraint> pushes;
  for (int round = 0; round < kMaxProjectionRounds; ++round) {
    pushes.clear();
    for (std::size_t b = 0; b < surfaces.size(); ++b) {
      if (!surfaces[b].hierarchy) continue;
      Push push = push_out(surfaces[b], b, centre, travel);
      if (!push.status.ok()) return {std::move(push.status), centre};
      const Eigen::Vector3d move = push.centre - centre;
      const double length = move.norm();
      if (push.moved && length > 0.0) pushes.push_back({move / length, length});
    }
    if (pushes.empty()) break;
    const Eigen::Vector3d pushed = push_apart(pushes);
    centre += pushed;
    travel += pushed.norm();  // a push may carry the centre through another surface
  }
  return {Status::success(), centre};
}

SphereMove SphereProxy::move(const std::vector<TrimmedSurface>& surfaces,
                             const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
  const double step = std::max(0.5 * radius_, 10.0 * eps_);
  const int count =
      std::clamp(static_cast<int>(std::ceil((to - from).norm() / step)), 1, kMaxSubsteps);
  const Eigen::Vector3d increment = (to - from) / count;
  SphereMove at = project(surfaces, from);
  for (int k = 0; k < count && at.status.ok(); ++k)
    at = project(surfaces, at.p_WT + increment, increment.norm());
  return at;
}

ProxyContact SphereProxy::nearest(const std::vector<TrimmedSurface>& surfaces,
                                  const Eigen::Vector3d& centre) {
  ProxyContact best;
  std::vector<double> clearances(surfaces.size());
  std::vector<Eigen::Vector3d> normals(surfaces.size());
  std::vector<char> skipped(surfaces.size(), 0);
  walk_to(centre);
  // A surface certainly farther than eps beyond the nearest's distance as
  // found (within eps/4 of some surface's bound) is neither the nearest nor
  // in the blend below: the answer is the same without querying it.
  std::vector<DistanceBounds> bounds(surfaces.size());
  double nearest_at_most = std::numeric_limits<double>::infinity();
  for (std::size_t b = 0; b < surfaces.size(); ++b)
    if (surfaces[b].hierarchy) {
      bounds[b] = distance_bounds(surfaces[b], b);
      nearest_at_most = std::min(nearest_at_most, bounds[b].at_most);
    }
  for (std::size_t b = 0; b < surfaces.size(); ++b) {
    if (!surfaces[b].hierarchy || bounds[b].at_least > nearest_at_most + 1.25 * eps_) {
      skipped[b] = 1;
      continue;
    }
    // Not recorded: a record vouches for the path since, and nearest() does
    // not follow the sides along it.
    ClosestPoint cp = closest(surfaces[b], b, centre, false);
    if (!cp.status.ok()) return {std::move(cp.status)};
    const double clearance = cp.distance - radius_;
    const int s = side(b) == 0 ? (cp.signed_distance < 0.0 ? -1 : 1) : side(b);
    clearances[b] = clearance;
    normals[b] = cp.distance > 1e-3 * eps_ ? Eigen::Vector3d((centre - cp.point) / cp.distance)
                                           : Eigen::Vector3d(s * cp.normal);
    if (best.body >= 0 && clearance >= best.clearance) continue;
    best.body = static_cast<int>(b);
    best.clearance = clearance;
    best.point = cp.point;
  }
  if (best.body < 0) return best;
  // In a groove or at a seam two surfaces are nearest by turns, tick after
  // tick; the normal blends every surface within eps of the nearest, each
  // weighted by how much closer than that band it is, so it turns smoothly
  // instead of jumping between the faces' normals.
  Eigen::Vector3d blend = Eigen::Vector3d::Zero();
  for (std::size_t b = 0; b < surfaces.size(); ++b) {
    if (skipped[b]) continue;
    const double weight = best.clearance + eps_ - clearances[b];
    if (weight > 0.0) blend += weight * normals[b];
  }
  best.outward_normal = blend.norm() > 0.0 ? Eigen::Vector3d(blend.normalized())
                                           : normals[static_cast<std::size_t>(best.body)];
  return best;
}

}  // namespace argil
