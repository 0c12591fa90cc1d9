// The B-spline tool's part of HapticWorld::step: the tool proxy advances
// conservatively, sticks or slips, and its contacts with every body. The
// advance tests crossings against the whole surfaces; contacts outside a
// body's trims are dropped (material only), for friction and load alike.
#include <optional>

#include "argil/core/deform/contact_response.hpp"
#include "argil/core/haptic/haptic_tick.hpp"

namespace argil {

HapticWorld::ProxyMove HapticWorld::move_surface_tool(const ProxyState& previous,
                                                      const DeviceSample& device,
                                                      const std::vector<char>& reach) {
  const std::vector<const SurfaceHierarchy*> surfs = surfaces(reach);
  const double k = options_.coupling.stiffness;
  ProxyMove out;
  // Where the proxy ends this tick: set by friction when it decides the tick,
  // else by a move towards the device.
  std::optional<ToolMove> moved;
  // The contacts at the stick point when they were queried, kept when the
  // proxy sticks there (the surfaces do not move within the proxy's part of
  // the tick).
  std::optional<ToolContacts> at_stick;
  if (previous.in_contact) {
    // Friction: the stick point keeps the last position with the new rotation.
    const Pose stick{device.X_WD.R, previous.X_WT.p};
    Eigen::Vector3d normal = previous.contact_normal;
    int touched = previous.touched_body;
    bool clear = false;
    if (device.X_WD.R.coeffs() == previous.X_WT.R.coeffs()) {
      // The tool has not turned: last tick's contacts at this very pose give
      // the cone's normal and body. Two yes/no queries tell whether the stick
      // point still touches the bodies as they stepped since, without
      // crossing them; a full contact query costs several times more.
      SurfaceToolProxy::Probe c = surface_tool_->crossing(surfs, stick);
      if (!c.status.ok()) return {std::move(c.status), {}, {}, {0, 0, 0}};
      clear = !c.found;
      if (clear) {
        SurfaceToolProxy::Probe t = surface_tool_->touching(surfs, stick);
        if (!t.status.ok()) return {std::move(t.status), {}, {}, {0, 0, 0}};
        if (!t.found) touched = -1;
      }
    } else {
      ToolContacts at = surface_tool_->contacts(surfs, stick);
      if (!at.status.ok()) return {std::move(at.status), {}, {}, {0, 0, 0}};
      drop_contacts_outside_trims(at.per_surface);
      normal = at.outward_normal;
      touched = -1;
      for (int b = 0; b < body_count() && touched < 0; ++b)
        if (!at.per_surface[static_cast<std::size_t>(b)].empty()) touched = b;
      clear = !at.crosses;
      at_stick = std::move(at);
    }
    if (clear && touched >= 0) {
      const FrictionOutcome fr =
          coulomb_friction(k * (device.X_WD.p - stick.p), normal, friction(touched), k);
      if (fr.normal_force > 0.0) {
        out.next.stuck = fr.stick;
        if (fr.stick) {
          moved = ToolMove{Status::success(), stick};
        } else {
          Pose slid = stick;
          slid.p += fr.slide;
          // The stick point crosses nothing (just tested): no push-out query.
          moved = surface_tool_->move(surfs, stick, slid, SurfaceToolProxy::Start::clear);
        }
      }
    }
    if (!out.next.stuck) at_stick.reset();  // the proxy does not end at the stick point
  }
  if (!moved) moved = surface_tool_->move(surfs, previous.X_WT, device.X_WD);
  if (!moved->status.ok()) return {std::move(moved->status), {}, {}, {0, 0, 0}};
  // The proxy keeps the device's rotation; its position is where the move stopped.
  out.next.X_WT = {device.X_WD.R, moved->X_WT.p};
  ToolContacts at = at_stick ? std::move(*at_stick) : surface_tool_->contacts(surfs, moved->X_WT);
  if (!at.status.ok()) return {std::move(at.status), {}, {}, {0, 0, 0}};
  if (!at_stick) drop_contacts_outside_trims(at.per_surface);
  out.body_contacts = std::move(at.per_surface);
  out.outward_normal = at.outward_normal;
  return out;
}

}  // namespace argil
