#include "argil/core/haptic/sphere_proxy.hpp"

#include <algorithm>
#include <cmath>

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

int& SphereProxy::side(std::size_t index) {
  if (sides_.size() <= index) sides_.resize(index + 1, 0);
  return sides_[index];
}

SphereProxy::Push SphereProxy::push_out(const TrimmedSurface& surface, std::size_t index,
                                        const Eigen::Vector3d& c) {
  ClosestPoint cp = closest_point(surface, c, {.tolerance = 0.25 * eps_});
  if (!cp.status.ok()) return {std::move(cp.status), c, false};
  const bool boundary = on_boundary(surface.hierarchy->surface(), cp);
  int& s = side(index);
  const double tiny = 1e-3 * eps_;  // below it the sign of a distance is noise
  if (s == 0) s = cp.signed_distance < 0.0 ? -1 : 1;
  const bool crossed = s * cp.signed_distance < -tiny && !boundary;
  if (!crossed && cp.distance >= radius_) {
    if (cp.distance > radius_ + tiny && std::abs(cp.signed_distance) > tiny && boundary)
      s = cp.signed_distance < 0.0 ? -1 : 1;  // went round the edge
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
                                const Eigen::Vector3d& start) {
  Eigen::Vector3d centre = start;
  for (int round = 0; round < 8; ++round) {
    bool moved = false;
    for (std::size_t b = 0; b < surfaces.size(); ++b) {
      Push push = push_out(surfaces[b], b, centre);
      if (!push.status.ok()) return {std::move(push.status), centre};
      centre = push.centre;
      moved = push.moved || moved;
    }
    if (!moved) break;
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
  for (int k = 0; k < count && at.status.ok(); ++k) at = project(surfaces, at.p_WT + increment);
  return at;
}

ProxyContact SphereProxy::nearest(const std::vector<TrimmedSurface>& surfaces,
                                  const Eigen::Vector3d& centre) {
  ProxyContact best;
  for (std::size_t b = 0; b < surfaces.size(); ++b) {
    ClosestPoint cp = closest_point(surfaces[b], centre, {.tolerance = 0.25 * eps_});
    if (!cp.status.ok()) return {std::move(cp.status)};
    const double clearance = cp.distance - radius_;
    if (best.body >= 0 && clearance >= best.clearance) continue;
    best.body = static_cast<int>(b);
    best.clearance = clearance;
    best.point = cp.point;
    const int s = side(b) == 0 ? (cp.signed_distance < 0.0 ? -1 : 1) : side(b);
    best.outward_normal = cp.distance > 1e-3 * eps_
                              ? Eigen::Vector3d((centre - cp.point) / cp.distance)
                              : Eigen::Vector3d(s * cp.normal);
  }
  return best;
}

}  // namespace argil
