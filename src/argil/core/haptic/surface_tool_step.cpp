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

bool touches(const ToolContacts& at) {
  return std::any_of(at.per_surface.begin(), at.per_surface.end(),
                     [](const std::vector<Contact>& c) { return !c.empty(); });
}

}  // namespace

HapticWorld::ProxyMove HapticWorld::move_surface_tool(const ProxyState& previous,
                                                      const DeviceSample& device,
                                                      const std::vector<char>& reach) {
  const std::vector<const SurfaceHierarchy*> surfs = surfaces(reach);
  // The bodies' trims, set for this tick's queries only: the proxy holds no
  // pointers into the world between ticks.
  std::vector<const TrimRegion*> materials;
  for (int b = 0; b < body_count(); ++b) materials.push_back(&trim(b));
  surface_tool_->set_materials(std::move(materials));
  struct ClearMaterials {
    SurfaceToolProxy& proxy;
    ~ClearMaterials() { proxy.set_materials({}); }
  } clear_materials{*surface_tool_};
  const double k = options_.coupling.stiffness;
  ProxyMove out;
  // Where the proxy ends this tick and its contacts there: set by friction
  // when it decides the tick, else by a move towards the device.
  std::optional<ToolMove> moved;
  // The contacts at the stick point when it was tested and crosses nothing.
  std::optional<ToolContacts> at_stick;
  std::optional<Pose> stick_point;
  if (previous.in_contact && previous.friction >= 0.0) {
    // Friction, explicit: stick or slip is decided with the normal and the
    // body of the contacts the last tick ended with. The stick point keeps
    // the last position with the new rotation, settled towards the surface.
    const Pose held{device.X_WD.R, previous.X_WT.p};
    const Eigen::Vector3d& n = previous.outward_normal;
    // Settling: a tool left far off the surfaces it touches (the body dented
    // away under it, or a slip along the contacts' tangent plane rose off a
    // curved face) comes down along the normal, never past the device.
    // Without it the gap grows tick by tick under a pressing hand until the
    // contact is lost, and the force drops to zero and jumps back. It aims
    // at 3/4 eps (close enough to keep the contact, far enough that few leaf
    // pairs lie within eps, so the queries cost what they did), less half of
    // how far the surfaces drew away since the last tick settled it (all of
    // it overshoots: the gap then swings from tick to tick), down to eps / 4.
    const double eps = options_.tolerance;
    const double gap = -previous.max_depth;
    const double receding =
        previous.settled_gap >= 0.0 ? std::max(gap - previous.settled_gap, 0.0) : 0.0;
    const double aim = std::clamp(0.75 * eps - 0.5 * receding, 0.25 * eps, 0.75 * eps);
    const double below = std::max(-n.dot(device.X_WD.p - held.p), 0.0);
    // At most 3/4 eps: one swept slip away (SurfaceToolProxy::slip).
    const double settle = std::clamp(gap - aim, 0.0, std::min(below, 0.75 * eps));
    Pose stick = held;
    Pose slid = held;
    FrictionOutcome fr;
    std::optional<ToolContacts> at;
    bool one_query = false;
    // A slip longer than eps from a stick point found clear: moved below.
    bool long_slip = false;
    double settled = 0.0;
    // Settled first; where the settled stick point crosses (the surface
    // sprang back towards the tool), as the last tick left it.
    for (const double by : {settle, 0.0}) {
      stick.p = held.p - by * n;
      fr = coulomb_friction(k * (device.X_WD.p - stick.p), n, previous.friction, k);
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
        SurfaceToolProxy::Crossing c = surface_tool_->crossing(
            surfs, stick, by == 0.0 ? std::nullopt : std::optional<Pose>(held));
        if (!c.status.ok()) return {std::move(c.status), {}, {}, {0, 0, 0}};
        long_slip = !c.crosses;
        if (long_slip || by == 0.0) break;
        continue;
      }
      // One query for the tick: at the stick point, or swept along a slip of
      // at most eps (a translation: both poses have the device's rotation)
      // from where the tool was. Pulled off, or where that slip's way
      // crosses, the tool queries its stick point's contacts first, and
      // moves from there. The stick point's
      // contacts are used only when it crosses nothing, so its query stops at
      // a crossing (a turn the proxy could not follow crosses there tick
      // after tick).
      if (fr.normal_force > 0.0) {
        at = fr.stick && by == 0.0 ? surface_tool_->contacts_unless_crossing(surfs, stick)
                                   : surface_tool_->slip(surfs, held, fr.stick ? stick : slid);
      }
      // A slip whose way crosses (a crease, a bump ahead) is taken as below.
      if (at && !fr.stick && at->status.ok() && at->crosses) at.reset();
      one_query = at.has_value();
      if (!at) {
        at = by == 0.0 ? surface_tool_->contacts_unless_crossing(surfs, stick)
                       : surface_tool_->slip(surfs, held, stick);
      }
      if (by == 0.0 || !at->status.ok() || !at->crosses) break;
    }
    if (long_slip) {
      moved = surface_tool_->move(surfs, stick, slid, SurfaceToolProxy::Start::clear);
      if (moved->status.ok() && touches(moved->contacts)) {
        out.next.settled_gap = gap - settled;
      } else if (moved->status.ok()) {
        // Slid off what it touched: on towards the device from there, clear.
        const ToolMove off = std::move(*moved);
        moved = surface_tool_->move(surfs, off.X_WT, device.X_WD, SurfaceToolProxy::Start::clear,
                                    &off.contacts);
      }
    } else if (at && !at->status.ok()) {
      return {std::move(at->status), {}, {}, {0, 0, 0}};
    } else if (!at) {
      // A slip longer than eps whose stick point crosses: moved from where
      // the tool was, below.
    } else if (fr.normal_force > 0.0 && !at->crosses && touches(*at)) {
      out.next.stuck = fr.stick;
      out.next.settled_gap = gap - settled;
      if (one_query) {
        moved = ToolMove{Status::success(), fr.stick ? stick : slid, std::move(*at)};
      } else {
        // The stick point crosses nothing (just tested): no push-out query.
        moved = surface_tool_->move(surfs, stick, slid, SurfaceToolProxy::Start::clear, &*at);
      }
    } else if (one_query && !fr.stick && !at->crosses) {
      // The slip ends clear, off the material (the body's step drew it away):
      // the move towards the device starts there, known clear.
      moved = surface_tool_->move(surfs, slid, device.X_WD, SurfaceToolProxy::Start::clear, &*at);
    } else if (!at->crosses) {
      // Here `at` is the stick point's (a swept slip clear of everything was
      // taken above).
      at_stick = std::move(at);
      stick_point = stick;
    }
  }
  if (!moved) {
    // An unturned tool's stick point is where the move starts, and a settled
    // one's (reached by a swept slip, its turn tested as a pose like any
    // stick point's): when it was found clear there, the move's own test of
    // its start is not repeated, and a move blocked where it starts keeps its
    // contacts.
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
