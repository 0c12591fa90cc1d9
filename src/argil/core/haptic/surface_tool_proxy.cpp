#include "argil/core/haptic/surface_tool_proxy.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>

#include "argil/core/base/number_text.hpp"
#include "argil/core/collision/contact.hpp"
#include "argil/core/collision/surface_intersection.hpp"

namespace argil {

SurfaceToolProxy::SurfaceToolProxy(const BSplineSurface& tool, SurfaceHierarchy hierarchy,
                                   double eps, int max_contacts)
    : hierarchy_(std::move(hierarchy)),
      centre_T_(tool.control_points.colwise().mean().transpose()),
      eps_(eps),
      size_(control_point_box(tool).diagonal()),
      reach_(tool.control_points.rowwise().norm().maxCoeff()),
      max_contacts_(max_contacts) {}

Result<SurfaceToolProxy> SurfaceToolProxy::create(const BSplineSurface& tool, double eps,
                                                  OperatorCache& cache, int max_contacts) {
  Result<SurfaceHierarchy> h = SurfaceHierarchy::build(tool, cache);
  if (!h.ok()) return h.status();
  // Every query of the tool runs at eps: a tool that eps cannot resolve (eps
  // above its size) would touch nothing and pass through every surface.
  if (Status s = check_request({.tolerance = eps, .max_contacts = max_contacts}, h.value());
      !s.ok()) {
    s.message = "a tool " + number_text(control_point_box(tool).diagonal()) +
                " mm across (its control points' box) is too small for the tolerance: " + s.message;
    return s;
  }
  return SurfaceToolProxy(tool, std::move(h).value(), eps, max_contacts);
}

ToolContacts SurfaceToolProxy::contacts(const std::vector<const SurfaceHierarchy*>& surfaces,
                                        const Pose& X_WT) {
  return contacts(surfaces, X_WT, std::nullopt, false);
}

ToolContacts SurfaceToolProxy::contacts(const std::vector<const SurfaceHierarchy*>& surfaces,
                                        const Pose& X_WT, const std::optional<Pose>& swept_from,
                                        bool partial_when_crossing) {
  // A proxy that sticks runs this query alone, tick after tick: the tool's
  // nodes are bounded here as well as in move().
  hierarchy_.keep_within_node_budget();
  const Eigen::Vector3d centre = apply(X_WT, centre_T_);
  ToolContacts out;
  Eigen::Vector3d off_material_normal = Eigen::Vector3d::Zero();
  out.per_surface.resize(surfaces.size());
  assert(materials_.empty() || materials_.size() == surfaces.size());
  for (std::size_t b = 0; b < surfaces.size(); ++b) {
    if (!surfaces[b]) continue;  // out of reach
    // Only contacts: a crossing is a contact of depth 0 (no curves chained).
    const CollisionRequest request{.tolerance = eps_,
                                   .max_contacts = max_contacts_,
                                   .refine = false,
                                   .compute_depth = false,
                                   .curves = false,
                                   .stop_at_crossing = partial_when_crossing,
                                   .material_a = materials_.empty() ? nullptr : materials_[b]};
    ++queries_.contacts;
    CollisionResult r = swept_from
                            ? collide_swept(*surfaces[b], hierarchy_, *swept_from, X_WT, request)
                            : collide(*surfaces[b], hierarchy_, X_WT, request);
    if (!r.status.ok()) {
      out.status = std::move(r.status);
      break;
    }
    // Contacts off the material (a trimmed-away part still blocks the tool)
    // count for crossing, and their crossings for the normal; their touches
    // give it only where the tool touches no material: friction presses on
    // the body, not on what was cut away.
    const auto add = [&](const std::vector<Contact>& touches, bool on_material) {
      for (const Contact& c : touches) {
        const bool crossing = c.depth >= 0.0;
        out.crosses = out.crosses || crossing;
        const double sign = c.normal.dot(centre - c.point) < 0.0 ? -1.0 : 1.0;
        (on_material || crossing ? out.outward_normal : off_material_normal) += sign * c.normal;
      }
    };
    add(r.contacts, true);
    add(r.off_material, false);
    out.per_surface[b] = std::move(r.contacts);
    // The caller uses partial contacts only when nothing crosses.
    if (partial_when_crossing && out.crosses) break;
  }
  if (out.outward_normal.squaredNorm() == 0.0) out.outward_normal = off_material_normal;
  if (out.outward_normal.squaredNorm() > 0.0) out.outward_normal.normalize();
  return out;
}

std::optional<ToolContacts> SurfaceToolProxy::slip(
    const std::vector<const SurfaceHierarchy*>& surfaces, const Pose& X_WT_from,
    const Pose& X_WT_to) {
  if (X_WT_from.R.coeffs() != X_WT_to.R.coeffs() || (X_WT_to.p - X_WT_from.p).norm() > eps_)
    return std::nullopt;
  return contacts(surfaces, X_WT_to, X_WT_from, true);
}

SurfaceToolProxy::Crossing SurfaceToolProxy::crossing(
    const std::vector<const SurfaceHierarchy*>& surfaces, const Pose& X_WT) {
  return crossing(surfaces, X_WT, std::nullopt);
}

SurfaceToolProxy::Crossing SurfaceToolProxy::crossing(
    const std::vector<const SurfaceHierarchy*>& surfaces, const Pose& X_WT,
    const std::optional<Pose>& swept_from) {
  // A yes/no test: the descent stops at the first crossing leaf pair.
  const CollisionRequest request{.tolerance = eps_,
                                 .max_contacts = 1,
                                 .refine = false,
                                 .compute_depth = false,
                                 .first_crossing_only = true,
                                 .curves = false};
  for (const SurfaceHierarchy* surface : surfaces) {
    if (!surface) continue;
    ++queries_.crossings;
    CollisionResult r = swept_from ? collide_swept(*surface, hierarchy_, *swept_from, X_WT, request)
                                   : collide(*surface, hierarchy_, X_WT, request);
    // A failed query counts as crossing: the proxy must not move where it
    // cannot prove it is clear.
    if (!r.status.ok()) return {std::move(r.status), true};
    if (!r.contacts.empty()) return {Status::success(), true};
  }
  return {Status::success(), false};
}

SurfaceToolProxy::Advance SurfaceToolProxy::bisect(
    const std::vector<const SurfaceHierarchy*>& surfaces, const Pose& clear,
    const Pose& crossing_pose, bool swept) {
  // The search counts whole steps of eps / 2 along the way (the last one ends
  // at crossing_pose): where it stops is a step count the crossing tests
  // decide. Comparing the bracket's width with eps / 2 instead hung on
  // rounding, as doubling then halving makes that width exactly eps / 2.
  const double span = (crossing_pose.p - clear.p).norm();
  // A way shorter than a step (or not a length) stops where it starts.
  if (!(span > 0.5 * eps_) || !std::isfinite(span))
    return {Status::success(), clear, true, std::nullopt};
  const double step = 0.5 * eps_ / span;
  const std::int64_t steps = static_cast<std::int64_t>(std::ceil(std::min(1.0 / step, 1e15)));
  std::int64_t lo = 0, hi = steps;
  const auto at = [&](std::int64_t n) {
    return n == 0 ? clear
                  : interpolate(clear, crossing_pose,
                                n >= steps ? 1.0 : static_cast<double>(n) * step);
  };
  // Swept, each test sweeps from the last pose found clear, so the stop is
  // reached without crossing on the way.
  const auto test = [&](std::int64_t n) -> std::optional<Status> {
    Crossing c = crossing(surfaces, at(n), swept ? std::optional<Pose>(at(lo)) : std::nullopt);
    if (!c.status.ok()) return std::move(c.status);
    (c.crosses ? hi : lo) = n;
    return std::nullopt;
  };
  // A tool resting on a surface is blocked within a few eps of where it
  // starts: one step ahead first, doubling, before halving the interval.
  for (std::int64_t n = 1; n < hi && hi - lo > 1; n *= 2)
    if (std::optional<Status> failed = test(n))
      return {std::move(*failed), at(lo), true, std::nullopt};
  for (int i = 0; i < kMaxBisections && hi - lo > 1; ++i)
    if (std::optional<Status> failed = test(lo + (hi - lo) / 2))
      return {std::move(*failed), at(lo), true, std::nullopt};
  return {Status::success(), at(lo), true, std::nullopt};
}

SurfaceToolProxy::Advance SurfaceToolProxy::stop_before(
    const std::vector<const SurfaceHierarchy*>& surfaces, const Pose& clear,
    const Pose& crossing_pose) {
  // Searched with tests at poses, then confirmed by one swept query from
  // `clear` (whose contacts are the stop's): only when the way there crosses
  // (a thin part of the tool passed through a surface between two tested
  // poses) is the search run again with swept tests.
  Advance quick = bisect(surfaces, clear, crossing_pose, false);
  // A failed search stops at `clear`: its last pose was never tested swept.
  if (!quick.status.ok()) return {std::move(quick.status), clear, true, std::nullopt};
  if (quick.X_WT.p == clear.p) return quick;
  ToolContacts at = contacts(surfaces, quick.X_WT, clear, true);
  if (!at.status.ok()) return {std::move(at.status), clear, true, std::nullopt};
  if (at.crosses) return bisect(surfaces, clear, quick.X_WT, true);
  quick.contacts = std::move(at);
  return quick;
}

SurfaceToolProxy::Advance SurfaceToolProxy::advance(
    const std::vector<const SurfaceHierarchy*>& surfaces, const Pose& from, const Pose& to) {
  const double length = (to.p - from.p).norm();
  const double step = std::max(0.25 * size_, 10.0 * eps_);
  // Substeps also turn the tool little enough that its points' arcs stay
  // within eps / 4 of the straight lines the swept test assumes:
  // reach (1 - cos(angle / 2)) <= eps / 4 (up to 256 substeps: beyond, the
  // arcs stray further, which the swept bounds still cover; only how deep a
  // graze the leaf test can miss or report grows, see collide_swept).
  const double turn = from.R.angularDistance(to.R);
  const double max_turn = 2.0 * std::acos(std::max(0.0, 1.0 - 0.25 * eps_ / reach_));
  const double substeps = std::max(std::ceil(length / step), std::ceil(turn / max_turn));
  const int count = static_cast<int>(std::clamp(substeps, 1.0, 256.0));
  Pose good = from;
  for (int k = 1; k < count; ++k) {
    const Pose next = interpolate(from, to, static_cast<double>(k) / count);
    Crossing c = crossing(surfaces, next, good);
    if (!c.status.ok()) return {std::move(c.status), good, true, std::nullopt};
    if (c.crosses) return stop_before(surfaces, good, next);
    good = next;
  }
  // The last substep: the contact query answers the crossing test too, and
  // its contacts are the move's when it crosses nothing.
  const Pose end = interpolate(from, to, 1.0);
  ToolContacts at = contacts(surfaces, end, good, true);
  if (!at.status.ok()) return {std::move(at.status), good, true, std::nullopt};
  if (at.crosses) return stop_before(surfaces, good, end);
  return {Status::success(), end, false, std::move(at)};
}

namespace {

bool same_pose(const Pose& a, const Pose& b) { return a.p == b.p && a.R.coeffs() == b.R.coeffs(); }

}  // namespace

ToolMove SurfaceToolProxy::arrive(const std::vector<const SurfaceHierarchy*>& surfaces, Advance end,
                                  const Pose& known_at, const ToolContacts* known) {
  if (!end.status.ok()) return {std::move(end.status), end.X_WT, {}};
  if (!end.contacts)
    end.contacts = known && same_pose(end.X_WT, known_at) ? *known : contacts(surfaces, end.X_WT);
  Status status = end.contacts->status;
  return {std::move(status), end.X_WT, std::move(*end.contacts)};
}

ToolMove SurfaceToolProxy::push_out(const std::vector<const SurfaceHierarchy*>& surfaces,
                                    const Pose& from, const Pose& to) {
  Pose start = from;
  // The yes/no test first: most moves start clear of every surface.
  Crossing clear = crossing(surfaces, start);
  if (!clear.status.ok() || !clear.crosses) return {std::move(clear.status), start, {}};
  ToolContacts at_start = contacts(surfaces, start);
  // Pushed out along the contact normal by doubling distances when the start crosses.
  for (double push = eps_; at_start.status.ok() && at_start.crosses && push < 4.0 * size_;
       push *= 2.0) {
    const Eigen::Vector3d n = at_start.outward_normal.squaredNorm() > 0.0
                                  ? at_start.outward_normal
                                  : Eigen::Vector3d((from.p - to.p).normalized());
    Pose out = start;
    out.p += push * n;
    at_start = contacts(surfaces, out);
    if (at_start.status.ok() && !at_start.crosses) start = out;
  }
  return {std::move(at_start.status), start, {}};
}

ToolMove SurfaceToolProxy::move(const std::vector<const SurfaceHierarchy*>& surfaces,
                                const Pose& X_WT_from, const Pose& X_WT_to, Start from,
                                const ToolContacts* at_from) {
  // The tool is never re-posed, so its nodes only grow: bound them here.
  hierarchy_.keep_within_node_budget();
  ToolMove start = from == Start::clear ? ToolMove{Status::success(), X_WT_from, {}}
                                        : push_out(surfaces, X_WT_from, X_WT_to);
  if (!start.status.ok()) return start;
  if (from != Start::clear) at_from = nullptr;
  Advance stop = advance(surfaces, start.X_WT, X_WT_to);
  if (!stop.status.ok() || !stop.blocked)
    return arrive(surfaces, std::move(stop), X_WT_from, at_from);
  // Slide: the rest of the move without its component into the surface. A
  // search's stop comes with its contacts (its confirming swept query), and
  // one that did not leave the start has the caller's.
  ToolContacts touch = stop.contacts                                ? std::move(*stop.contacts)
                       : at_from && same_pose(stop.X_WT, X_WT_from) ? *at_from
                                                                    : contacts(surfaces, stop.X_WT);
  if (!touch.status.ok()) return {std::move(touch.status), stop.X_WT, {}};
  Eigen::Vector3d rest = X_WT_to.p - stop.X_WT.p;
  const double into = rest.dot(touch.outward_normal);
  if (into < 0.0) rest -= into * touch.outward_normal;
  // A slide shorter than the stop's own resolution (eps / 2) is not tried
  // (the proxy then lags the hand by at most that much sideways).
  if (rest.norm() <= 0.5 * eps_ && stop.X_WT.R.coeffs() == X_WT_to.R.coeffs())
    return {Status::success(), stop.X_WT, std::move(touch)};
  Pose slide_to = X_WT_to;
  slide_to.p = stop.X_WT.p + rest;
  return arrive(surfaces, advance(surfaces, stop.X_WT, slide_to), stop.X_WT, &touch);
}

}  // namespace argil
