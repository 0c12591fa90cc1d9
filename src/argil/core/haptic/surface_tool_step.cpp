// The B-spline tool's part of HapticWorld::step: the tool proxy advances
// conservatively, sticks or slips, and its contacts with every body. The
// advance tests crossings against the whole surfaces; its contacts are the
// bodies' material only (its queries set the rest apart), for friction and
// load alike.
#include <algorithm>
#include <optional>

#include "argil/core/deform/contact_response.hpp"
#include "argil/core/haptic/haptic_tick.hpp"

namespace argil {

namespace {

using Surfaces = std::vector<const SurfaceHierarchy*>;

bool touches(const ToolContacts& at) {
  return std::any_of(at.per_surface.begin(), at.per_surface.end(),
                     [](const std::vector<Contact>& c) { return !c.empty(); });
}

/// How far the stick point comes down towards the surfaces this tick.
/// A tool left far off the surfaces it touches (the body dented away under
/// it, or a slip along the contacts' tangent plane rose off a curved face)
/// comes down along the normal, never past the device. Without it the gap
/// grows tick by tick under a pressing hand until the contact is lost, and
/// the force drops to zero and jumps back. It aims at 3/4 eps (close enough
/// to keep the contact, far enough that few leaf pairs lie within eps, so the
/// queries cost what they did), less half of how far the surfaces drew away
/// since the last tick settled it (all of it overshoots: the gap then swings
/// from tick to tick), down to eps / 4.
struct Settling {
  double gap = 0.0;     // how far off the surfaces the last tick left the tool [mm]
  double aim = 0.0;     // the gap the tool comes down to [mm]
  double below = 0.0;   // how far the hand is below the tool, along the normal [mm]
  double settle = 0.0;  // how far the tool comes down [mm]

  Settling(const ProxyState& previous, const Pose& held, const Eigen::Vector3d& hand, double eps)
      : gap(-previous.max_depth) {
    const double receding = previous.settled_gap ? std::max(gap - *previous.settled_gap, 0.0) : 0.0;
    aim = std::clamp(0.75 * eps - 0.5 * receding, 0.25 * eps, 0.75 * eps);
    below = std::max(-previous.outward_normal.dot(hand - held.p), 0.0);
    // At most 3/4 eps: one swept slip away (SurfaceToolProxy::slip).
    settle = std::clamp(gap - aim, 0.0, std::min(below, 0.75 * eps));
  }
  /// The hand deeper than where the tool comes down to: friction decides.
  bool pressing() const { return below > std::max(gap - aim, 0.0); }
};

/// Where friction leaves the tool this tick: `moved` when it decides the
/// tick; else the move towards the device decides it, from `stick_point`
/// (with its contacts, `at_stick`) when that was found clear.
struct [[nodiscard]] FrictionMove {
  Status status;
  std::optional<ToolMove> moved;
  std::optional<ToolContacts> at_stick;
  std::optional<Pose> stick_point;
};

/// A tool clear of the surfaces but touching nothing where friction put it
/// (`from`; the surfaces drew away further than the settle followed: under a
/// steady press the gap creeps up to eps tick by tick) settles on by one more
/// swept slip of at most 3/4 eps along the normal `n`, not past the hand.
/// One query finds the surfaces again, where the move towards the device
/// would search for its stop with up to a dozen crossing tests and slide on
/// frictionless. Nothing when that slip crosses or still touches nothing.
std::optional<ToolMove> settle_further(SurfaceToolProxy& tool, const Surfaces& surfs,
                                       const Pose& from, const Eigen::Vector3d& n,
                                       const Eigen::Vector3d& hand, double eps) {
  const double by = std::min(0.75 * eps, -n.dot(hand - from.p));
  if (!(by > 0.0)) return std::nullopt;
  Pose to = from;
  to.p -= by * n;
  std::optional<ToolContacts> c = tool.slip(surfs, from, to);
  if (!c) return std::nullopt;
  if (!c->status.ok()) return ToolMove{std::move(c->status), from, {}};
  if (c->crosses || !touches(*c)) return std::nullopt;
  return ToolMove{Status::success(), to, std::move(*c)};
}

/// Friction, explicit: stick or slip is decided with the normal and the body
/// of the contacts the last tick ended with. The stick point keeps the last
/// position with the new rotation, settled towards the surface. Sets
/// `next.stuck` and `next.settled_gap` when it decides the tick in contact.
FrictionMove friction_move(SurfaceToolProxy& tool, const Surfaces& surfs,
                           const ProxyState& previous, const DeviceSample& device, double eps,
                           double k, ProxyState& next) {
  const Pose held{device.X_WD.R, previous.X_WT.p};
  const Eigen::Vector3d& n = previous.outward_normal;
  const Eigen::Vector3d& hand = device.X_WD.p;
  const Settling settling(previous, held, hand, eps);
  const double gap = settling.gap;
  // The hand no deeper than where the tool comes down to (lifting off, or
  // resting on the surfaces without pressing): no normal force, no friction,
  // and the tool follows the hand. Within eps of where the tool was that is
  // one swept query, where the stick point's query and then the move's were
  // two contact queries (over a millisecond for a pad lying on a face). Not
  // tried for a turn that moves the tool's far points by more than its
  // clearance there (a turn blocked where the rim would dip in, the hand
  // turning on): that pose likely crosses, and the query would be wasted.
  const double turn = previous.X_WT.R.angularDistance(device.X_WD.R);
  if (!settling.pressing() && (hand - held.p).norm() <= eps &&
      turn * tool.reach() <= gap - settling.below) {
    std::optional<ToolContacts> free = tool.slip(surfs, held, device.X_WD);
    if (free && !free->status.ok()) return {std::move(free->status), {}, {}, {}};
    if (free && !free->crosses)
      return {
          Status::success(), ToolMove{Status::success(), device.X_WD, std::move(*free)}, {}, {}};
  }
  Pose stick = held;
  Pose slid = held;
  FrictionOutcome fr;
  std::optional<ToolContacts> at;
  bool one_query = false;
  // A slip longer than eps from a stick point found clear: moved below.
  bool long_slip = false;
  double settled = 0.0;
  // Settled on from `from` (see settle_further): the gap the tool then stands
  // at, as the next tick reads it, is the last tick's less both settles.
  const auto settled_further = [&](const Pose& from) {
    std::optional<ToolMove> on = settle_further(tool, surfs, from, n, hand, eps);
    if (on && on->status.ok()) next.settled_gap = gap - settled - n.dot(from.p - on->X_WT.p);
    return on;
  };
  // Settled first; where the settled stick point crosses (the surface
  // sprang back towards the tool), as the last tick left it.
  for (const double by : {settling.settle, 0.0}) {
    stick.p = held.p - by * n;
    fr = coulomb_friction(k * (hand - stick.p), n, previous.friction, k);
    slid = stick;
    slid.p += fr.slide;
    settled = by;
    at.reset();
    if (fr.normal_force > 0.0 && !fr.stick && (slid.p - held.p).norm() > eps) {
      // A slip longer than eps (a fast drag) moves from the stick point,
      // whose contacts it does not need: the yes/no test there (swept from
      // where the tool was when settled) costs a fraction of a contact
      // query (no leaf pair's distance is measured), and the move's last
      // query gives the contacts where the slip ends.
      SurfaceToolProxy::Crossing c =
          tool.crossing(surfs, stick, by == 0.0 ? std::nullopt : std::optional<Pose>(held));
      if (!c.status.ok()) return {std::move(c.status), {}, {}, {}};
      long_slip = !c.crosses;
      if (long_slip || by == 0.0) break;
      continue;
    }
    // One query for the tick: at the stick point, or swept along a slip of
    // at most eps (a translation: both poses have the device's rotation)
    // from where the tool was. Pulled off, or where that slip's way
    // crosses, the tool queries its stick point's contacts first, and
    // moves from there. The stick point's contacts are used only when it
    // crosses nothing, so its query stops at a crossing (a turn the proxy
    // could not follow crosses there tick after tick).
    if (fr.normal_force > 0.0) {
      at = fr.stick && by == 0.0 ? tool.contacts_unless_crossing(surfs, stick)
                                 : tool.slip(surfs, held, fr.stick ? stick : slid);
    }
    // A slip whose way crosses (a crease, a bump ahead) is taken as below.
    if (at && !fr.stick && at->status.ok() && at->crosses) at.reset();
    one_query = at.has_value();
    if (!at) {
      at = by == 0.0 ? tool.contacts_unless_crossing(surfs, stick) : tool.slip(surfs, held, stick);
    }
    if (by == 0.0 || !at->status.ok() || !at->crosses) break;
  }
  FrictionMove out;
  if (long_slip) {
    out.moved = tool.move(surfs, stick, slid, SurfaceToolProxy::Start::clear);
    if (out.moved->status.ok() && touches(out.moved->contacts)) {
      next.settled_gap = gap - settled;
    } else if (out.moved->status.ok()) {
      // Slid off what it touched: settled on, or on towards the device from
      // there, clear.
      const ToolMove off = std::move(*out.moved);
      out.moved = settled_further(off.X_WT);
      if (!out.moved) {
        out.moved =
            tool.move(surfs, off.X_WT, device.X_WD, SurfaceToolProxy::Start::clear, &off.contacts);
      }
    }
  } else if (at && !at->status.ok()) {
    out.status = std::move(at->status);
  } else if (!at) {
    // A slip longer than eps whose stick point crosses: moved from where
    // the tool was.
  } else if (fr.normal_force > 0.0 && !at->crosses && touches(*at)) {
    next.stuck = fr.stick;
    next.settled_gap = gap - settled;
    if (one_query) {
      out.moved = ToolMove{Status::success(), fr.stick ? stick : slid, std::move(*at)};
    } else {
      // The stick point crosses nothing (just tested): no push-out query.
      out.moved = tool.move(surfs, stick, slid, SurfaceToolProxy::Start::clear, &*at);
    }
  } else if (one_query && !fr.stick && !at->crosses) {
    // The slip ends clear, off the material (the body's step drew it away):
    // settled on from there, or the move towards the device starts there,
    // known clear.
    out.moved = settled_further(slid);
    if (!out.moved)
      out.moved = tool.move(surfs, slid, device.X_WD, SurfaceToolProxy::Start::clear, &*at);
  } else if (!at->crosses) {
    // Here `at` is the stick point's (a swept slip clear of everything was
    // taken above). Held there and pressed, it settles on. (A slip whose way
    // crossed moves from there towards the device, frictionless, as before.)
    if (fr.normal_force > 0.0 && fr.stick) out.moved = settled_further(stick);
    if (out.moved) {
      next.stuck = true;
    } else {
      out.at_stick = std::move(at);
      out.stick_point = stick;
    }
  }
  return out;
}

}  // namespace

HapticWorld::ProxyMove HapticWorld::move_surface_tool(const ProxyState& previous,
                                                      const DeviceSample& device,
                                                      const std::vector<char>& reach) {
  const Surfaces surfs = surfaces(reach);
  // The bodies' trims, set for this tick's queries only: the proxy holds no
  // pointers into the world between ticks.
  std::vector<const TrimRegion*> materials;
  for (int b = 0; b < body_count(); ++b) materials.push_back(&trim(b));
  surface_tool_->set_materials(std::move(materials));
  struct ClearMaterials {
    SurfaceToolProxy& proxy;
    ~ClearMaterials() { proxy.set_materials({}); }
  } clear_materials{*surface_tool_};
  ProxyMove out;
  // Where the proxy ends this tick and its contacts there: set by friction
  // when it decides the tick, else by a move towards the device.
  FrictionMove friction;
  if (previous.in_contact && previous.friction >= 0.0) {
    friction = friction_move(*surface_tool_, surfs, previous, device, options_.tolerance,
                             options_.coupling.stiffness, out.next);
    if (!friction.status.ok()) return {std::move(friction.status), {}, {}, {0, 0, 0}};
  }
  std::optional<ToolMove>& moved = friction.moved;
  if (!moved) {
    // An unturned tool's stick point is where the move starts, and a settled
    // one's (reached by a swept slip, its turn tested as a pose like any
    // stick point's): when it was found clear there, the move's own test of
    // its start is not repeated, and a move blocked where it starts keeps its
    // contacts.
    const std::optional<ToolContacts>& at_stick = friction.at_stick;
    const std::optional<Pose>& stick_point = friction.stick_point;
    const bool settled = at_stick && stick_point->p != previous.X_WT.p;
    const bool start_clear =
        at_stick && (settled || device.X_WD.R.coeffs() == previous.X_WT.R.coeffs());
    moved = surface_tool_->move(
        surfs, start_clear ? *stick_point : previous.X_WT, device.X_WD,
        start_clear ? SurfaceToolProxy::Start::clear : SurfaceToolProxy::Start::unknown,
        start_clear ? &*at_stick : nullptr);
  }
  if (!moved->status.ok()) return {std::move(moved->status), {}, {}, {0, 0, 0}};
  // The proxy's pose is where the move stopped, rotation too: a turn blocked
  // part way (a rim that would dip into a surface) keeps the tool where it is
  // clear, and the next tick turns on from there towards the hand.
  out.next.X_WT = moved->X_WT;
  out.body_contacts = std::move(moved->contacts.per_surface);
  out.outward_normal = moved->contacts.outward_normal;
  return out;
}

}  // namespace argil
