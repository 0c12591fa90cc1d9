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
  ToolMove moved = surface_tool_->move(surfs, previous.X_WT, device.X_WD);
  if (!moved.status.ok()) return {std::move(moved.status), {}, {}, {0, 0, 0}};
  // The contacts at the stick point, kept when the proxy sticks there (the
  // surfaces do not move within the proxy's part of the tick).
  std::optional<ToolContacts> at_stick;
  if (previous.in_contact) {
    // Friction: the stick point keeps the last position with the new rotation.
    const Pose stick{device.X_WD.R, previous.X_WT.p};
    ToolContacts at = surface_tool_->contacts(surfs, stick);
    if (!at.status.ok()) return {std::move(at.status), {}, {}, {0, 0, 0}};
    drop_contacts_outside_trims(at.per_surface);
    double mu = -1.0;  // of the first body touched
    for (int b = 0; b < body_count() && mu < 0.0; ++b)
      if (!at.per_surface[static_cast<std::size_t>(b)].empty()) mu = friction(b);
    if (!at.crosses && mu >= 0.0) {
      const FrictionOutcome fr =
          coulomb_friction(k * (device.X_WD.p - stick.p), at.outward_normal, mu, k);
      if (fr.normal_force > 0.0) {
        out.next.stuck = fr.stick;
        if (fr.stick) {
          moved.X_WT = stick;
          at_stick = std::move(at);
        } else {
          Pose slid = stick;
          slid.p += fr.slide;
          moved = surface_tool_->move(surfs, stick, slid);
          if (!moved.status.ok()) return {std::move(moved.status), {}, {}, {0, 0, 0}};
        }
      }
    }
  }
  // The proxy keeps the device's rotation; its position is where the move stopped.
  out.next.X_WT = {device.X_WD.R, moved.X_WT.p};
  ToolContacts at = at_stick ? std::move(*at_stick) : surface_tool_->contacts(surfs, moved.X_WT);
  if (!at.status.ok()) return {std::move(at.status), {}, {}, {0, 0, 0}};
  if (!at_stick) drop_contacts_outside_trims(at.per_surface);
  out.body_contacts = std::move(at.per_surface);
  out.outward_normal = at.outward_normal;
  return out;
}

}  // namespace argil
