// The sphere (or point) tool's part of HapticWorld::step: the god-object
// proxy moves, sticks or slips, and is collided with every body.
#include "argil/core/collision/implicit_contact.hpp"
#include "argil/core/deform/contact_response.hpp"
#include "argil/core/geometry/implicit_tool.hpp"
#include "argil/core/haptic/haptic_tick.hpp"

namespace argil {

HapticWorld::ProxyMove HapticWorld::move_sphere(const ProxyState& previous,
                                                const DeviceSample& device) {
  const double eps = options_.tolerance;
  const double k = options_.coupling.stiffness;
  const std::vector<SurfaceHierarchy*> surfs = surfaces();
  const Eigen::Vector3d& p_WD = device.X_WD.p;
  ProxyMove out;
  out.next.X_WT.R = device.X_WD.R;
  Eigen::Vector3d& p_WT = out.next.X_WT.p;
  p_WT = sphere_->move(surfs, previous.X_WT.p, p_WD);
  if (previous.in_contact) {
    // Friction: from the stick point, the pull decides stick or slip.
    const Eigen::Vector3d stick = sphere_->project(surfs, previous.X_WT.p);
    const ProxyContact at = sphere_->nearest(surfs, stick);
    if (at.body >= 0 && at.clearance <= eps) {
      const FrictionOutcome fr =
          coulomb_friction(k * (p_WD - stick), at.outward_normal, friction(at.body), k);
      if (fr.normal_force > 0.0) {
        out.next.stuck = fr.stick;
        p_WT = fr.stick ? stick : sphere_->move(surfs, stick, stick + fr.slide);
      }
    }
  }
  const auto tool = make_sphere(p_WT, sphere_->radius());
  out.body_contacts.resize(bodies_.size());
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    CollisionResult hit =
        collide(*surfs[b], *tool, {.tolerance = eps, .max_contacts = options_.max_contacts});
    if (!hit.status.ok()) {
      out.status =
          Status::error(hit.status.code, "body " + std::to_string(b) + ": " + hit.status.message);
      return out;
    }
    out.body_contacts[b] = std::move(hit.contacts);
  }
  out.outward_normal = sphere_->nearest(surfs, p_WT).outward_normal;
  return out;
}

}  // namespace argil
