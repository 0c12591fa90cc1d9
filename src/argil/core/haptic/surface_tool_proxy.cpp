#include "argil/core/haptic/surface_tool_proxy.hpp"

#include <algorithm>
#include <cmath>

#include "argil/core/collision/surface_intersection.hpp"

namespace argil {

namespace {

ToolPose interpolate(const ToolPose& a, const ToolPose& b, double t) {
  return {a.position + t * (b.position - a.position), a.orientation.slerp(t, b.orientation)};
}

}  // namespace

SurfaceToolProxy::SurfaceToolProxy(const BSplineSurface& tool, SurfaceHierarchy posed, double eps)
    : tool_points_(tool.control_points),
      posed_(std::move(posed)),
      eps_(eps),
      size_(control_point_box(tool).diagonal()) {}

Result<SurfaceToolProxy> SurfaceToolProxy::create(const BSplineSurface& tool, double eps,
                                                  OperatorCache& cache) {
  Result<SurfaceHierarchy> h = SurfaceHierarchy::build(tool, cache);
  if (!h.ok()) return h.status();
  return SurfaceToolProxy(tool, std::move(h).value(), eps);
}

void SurfaceToolProxy::place(const ToolPose& pose) {
  const Eigen::Matrix3d r = pose.orientation.normalized().toRotationMatrix();
  ControlNet world(tool_points_.rows(), 3);
  for (Eigen::Index k = 0; k < world.rows(); ++k)
    world.row(k) = (r * tool_points_.row(k).transpose() + pose.position).transpose();
  posed_.set_control_points(world);
}

ToolContacts SurfaceToolProxy::contacts(const std::vector<SurfaceHierarchy*>& surfaces,
                                        const ToolPose& pose) {
  place(pose);
  const Eigen::Vector3d centre = posed_.surface().control_points.colwise().mean().transpose();
  ToolContacts out;
  out.per_surface.resize(surfaces.size());
  for (std::size_t b = 0; b < surfaces.size(); ++b) {
    CollisionResult r =
        collide(*surfaces[b], posed_,
                {.tolerance = eps_, .max_contacts = 64, .refine = false, .compute_depth = false});
    out.crosses = out.crosses || !r.curves.empty();
    for (const Contact& c : r.contacts) {
      out.crosses = out.crosses || c.depth >= 0.0;
      const double sign = c.normal.dot(centre - c.point) < 0.0 ? -1.0 : 1.0;
      out.outward_normal += sign * c.normal;
    }
    out.per_surface[b] = std::move(r.contacts);
  }
  if (out.outward_normal.squaredNorm() > 0.0) out.outward_normal.normalize();
  return out;
}

bool SurfaceToolProxy::crosses(const std::vector<SurfaceHierarchy*>& surfaces,
                               const ToolPose& pose) {
  place(pose);
  // A yes/no test: the descent stops at the first crossing leaf pair.
  const CollisionRequest request{.tolerance = eps_,
                                 .max_contacts = 1,
                                 .refine = false,
                                 .compute_depth = false,
                                 .first_crossing_only = true};
  for (SurfaceHierarchy* surface : surfaces) {
    const CollisionResult r = collide(*surface, posed_, request);
    if (!r.contacts.empty() || !r.curves.empty()) return true;
  }
  return false;
}

ToolPose SurfaceToolProxy::advance(const std::vector<SurfaceHierarchy*>& surfaces,
                                   const ToolPose& from, const ToolPose& to, bool& blocked) {
  blocked = false;
  const double length = (to.position - from.position).norm();
  const double step = std::max(0.25 * size_, 10.0 * eps_);
  const int count = std::clamp(static_cast<int>(std::ceil(length / step)), 1, 256);
  ToolPose good = from;
  for (int k = 1; k <= count; ++k) {
    const ToolPose next = interpolate(from, to, static_cast<double>(k) / count);
    if (!crosses(surfaces, next)) {
      good = next;
      continue;
    }
    // Bisect between `good` (clear) and `next` (crossing).
    double lo = 0.0, hi = 1.0;
    const ToolPose start = good;
    const double span = (next.position - start.position).norm();
    for (int i = 0; i < kMaxBisections && (hi - lo) * span > 0.5 * eps_; ++i) {
      const double mid = 0.5 * (lo + hi);
      if (crosses(surfaces, interpolate(start, next, mid)))
        hi = mid;
      else
        lo = mid;
    }
    good = interpolate(start, next, lo);
    blocked = true;
    return good;
  }
  return good;
}

ToolPose SurfaceToolProxy::move(const std::vector<SurfaceHierarchy*>& surfaces,
                                const ToolPose& from, const ToolPose& to) {
  ToolPose start = from;
  ToolContacts at_start = contacts(surfaces, start);
  // Pushed out along the contact normal by doubling distances when the start crosses.
  for (double push = eps_; at_start.crosses && push < 4.0 * size_; push *= 2.0) {
    const Eigen::Vector3d n = at_start.outward_normal.squaredNorm() > 0.0
                                  ? at_start.outward_normal
                                  : Eigen::Vector3d((from.position - to.position).normalized());
    ToolPose out = start;
    out.position += push * n;
    at_start = contacts(surfaces, out);
    if (!at_start.crosses) start = out;
  }
  bool blocked = false;
  const ToolPose stop = advance(surfaces, start, to, blocked);
  if (!blocked) return stop;
  // Slide: the rest of the move without its component into the surface.
  const ToolContacts touch = contacts(surfaces, stop);
  Eigen::Vector3d rest = to.position - stop.position;
  const double into = rest.dot(touch.outward_normal);
  if (into < 0.0) rest -= into * touch.outward_normal;
  ToolPose slide_to = to;
  slide_to.position = stop.position + rest;
  return advance(surfaces, stop, slide_to, blocked);
}

}  // namespace argil
