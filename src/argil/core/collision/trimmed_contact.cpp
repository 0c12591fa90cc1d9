#include "argil/core/collision/trimmed_contact.hpp"

#include <algorithm>
#include <limits>

#include "argil/core/collision/detail/closest_search.hpp"
#include "argil/core/collision/detail/contact_regions.hpp"
#include "argil/core/collision/surface_contact.hpp"
#include "argil/core/geometry/evaluate.hpp"

namespace argil {

namespace {

bool trimmed(const TrimmedSurface& s) { return s.trim != nullptr && !s.trim->empty(); }

/// The region of the contact nearest to `point` among `dropped`.
int nearest_region(const std::vector<Contact>& dropped, const Eigen::Vector3d& point) {
  int region = 0;
  double best = std::numeric_limits<double>::infinity();
  for (const Contact& c : dropped) {
    const double d = (c.point - point).squaredNorm();
    if (d < best) {
      best = d;
      region = c.region;
    }
  }
  return region;
}

}  // namespace

ClosestPoint closest_point(const TrimmedSurface& s, const Eigen::Vector3d& p_W,
                           const CollisionRequest& request) {
  ClosestPoint whole = closest_point(*s.hierarchy, p_W, request);
  if (!whole.status.ok() || !trimmed(s) || s.trim->contains(whole.uv)) return whole;
  const BSplineSurface& surface = s.hierarchy->surface();
  QueryCounters counters = whole.counters;
  const TrimEdgePoint edge =
      closest_edge_search(*s.hierarchy, *s.trim, p_W, request.tolerance, counters);
  const ClosestFound inside = closest_point_search(
      *s.hierarchy, p_W, {.eps = request.tolerance, .trim = s.trim, .bound = edge.distance},
      counters);
  if (inside.distance < edge.distance) return closest_point_at(surface, inside.uv, p_W, counters);
  ClosestPoint out = closest_point_at(surface, edge.uv, p_W, counters);
  out.on_edge = true;
  return out;
}

CollisionResult collide_sphere(const TrimmedSurface& s, const Eigen::Vector3d& p_WC, double radius,
                               const CollisionRequest& request) {
  if (!trimmed(s)) return collide(*s.hierarchy, *make_sphere(p_WC, radius), request);
  // Every contact is looked at before they are kept to max_contacts: those
  // off the material would otherwise crowd out the ones on it.
  CollisionRequest all = request;
  all.max_contacts = std::numeric_limits<int>::max();
  CollisionResult result = collide(*s.hierarchy, *make_sphere(p_WC, radius), all);
  if (!result.status.ok()) return result;
  std::vector<Contact> dropped;
  std::erase_if(result.contacts, [&](const Contact& c) {
    if (s.trim->contains(c.uv_a)) return false;
    dropped.push_back(c);
    return true;
  });
  if (dropped.empty()) {
    rank_regions(result.contacts, result.region_count, request.max_contacts);
    return result;
  }
  const BSplineSurface& surface = s.hierarchy->surface();
  const TrimEdgePoint edge =
      closest_edge_search(*s.hierarchy, *s.trim, p_WC, request.tolerance, result.counters);
  if (edge.distance <= radius + request.tolerance) {
    const SurfaceDerivatives d = evaluate_derivatives(surface, edge.uv.x(), edge.uv.y(), 1);
    Contact c = contact_at(surface, edge.uv, d, radius - edge.distance);
    if (edge.distance > 0.0) c.normal = (p_WC - edge.point) / edge.distance;
    c.region = nearest_region(dropped, edge.point);
    result.contacts.push_back(c);
  }
  // At most max_contacts: a contact was dropped for the edge's one.
  rank_regions(result.contacts, result.region_count, request.max_contacts);
  int regions = 0;
  for (const Contact& c : result.contacts) regions = std::max(regions, c.region + 1);
  result.region_count = regions;
  return result;
}

}  // namespace argil
