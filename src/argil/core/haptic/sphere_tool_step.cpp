// The sphere (or point) tool's part of HapticWorld::step: the god-object
// proxy moves, sticks or slips, and is collided with every body.
#include <optional>

#include "argil/core/collision/trimmed_contact.hpp"
#include "argil/core/deform/contact_response.hpp"
#include "argil/core/haptic/haptic_tick.hpp"

namespace argil {

namespace {

/// Contacts of a sphere of `radius` [mm] centred at p_WT with every surface's material.
struct [[nodiscard]] SphereContacts {
  Status status;  // the first failed query's, naming its body
  std::vector<std::vector<Contact>> per_body;
};

SphereContacts sphere_contacts(const std::vector<TrimmedSurface>& surfaces,
                               const Eigen::Vector3d& p_WT, double radius,
                               const CollisionRequest& request) {
  SphereContacts out;
  out.per_body.resize(surfaces.size());
  for (std::size_t b = 0; b < surfaces.size(); ++b) {
    if (!surfaces[b].hierarchy) continue;  // out of reach
    CollisionResult hit = collide_sphere(surfaces[b], p_WT, radius, request);
    if (!hit.status.ok()) {
      out.status =
          Status::error(hit.status.code, "body " + std::to_string(b) + ": " + hit.status.message);
      return out;
    }
    out.per_body[b] = std::move(hit.contacts);
  }
  return out;
}

}  // namespace

HapticWorld::ProxyMove HapticWorld::move_sphere(const ProxyState& previous,
                                                const DeviceSample& device,
                                                const std::vector<char>& reach) {
  const double eps = options_.tolerance;
  const double k = options_.coupling.stiffness;
  const std::vector<TrimmedSurface> surfs = trimmed_surfaces(reach);
  // How far each body's surface moved since the proxy's last queries: its
  // last step (a surface springing back may have crossed the centre).
  // And how far any point of it can have moved: the bound the proxy passes
  // far surfaces by.
  std::vector<double> motion(bodies_.size(), 0.0), travel(bodies_.size(), 0.0);
  for (std::size_t b = 0; b < bodies_.size(); ++b)
    if (bodies_[b].deformable && !bodies_[b].asleep) {
      motion[b] = bodies_[b].deformable->last_step_motion();
      travel[b] = bodies_[b].deformable->last_step_travel();
    }
  sphere_->set_surface_motion(std::move(motion), std::move(travel));
  const Eigen::Vector3d& p_WD = device.X_WD.p;
  ProxyMove out;
  out.next.X_WT.R = device.X_WD.R;
  // In contact, friction decides from the stick point whether the proxy
  // sticks or slides; only a proxy out of contact (or pulled off) follows the
  // device freely. Moving it towards the device first, as if free, cost a
  // tick in contact eight closest-point queries whose result was dropped.
  std::optional<SphereMove> moved;
  if (previous.in_contact) {
    SphereMove stick = sphere_->project(surfs, previous.X_WT.p);
    if (!stick.status.ok()) return {std::move(stick.status), {}, {}, {0, 0, 0}};
    ProxyContact at = sphere_->nearest(surfs, stick.p_WT);
    if (!at.status.ok()) return {std::move(at.status), {}, {}, {0, 0, 0}};
    if (at.body >= 0 && at.clearance <= eps) {
      const FrictionOutcome fr =
          coulomb_friction(k * (p_WD - stick.p_WT), at.outward_normal, friction(at.body), k);
      if (fr.normal_force > 0.0) {
        out.next.stuck = fr.stick;
        moved = fr.stick ? stick : sphere_->move(surfs, stick.p_WT, stick.p_WT + fr.slide);
      }
    }
  }
  if (!moved) moved = sphere_->move(surfs, previous.X_WT.p, p_WD);
  if (!moved->status.ok()) return {std::move(moved->status), {}, {}, {0, 0, 0}};
  out.next.X_WT.p = moved->p_WT;
  SphereContacts hits = sphere_contacts(surfs, moved->p_WT, sphere_->radius(),
                                        {.tolerance = eps, .max_contacts = options_.max_contacts});
  if (!hits.status.ok()) return {std::move(hits.status), {}, {}, {0, 0, 0}};
  ProxyContact near = sphere_->nearest(surfs, moved->p_WT);
  if (!near.status.ok()) return {std::move(near.status), {}, {}, {0, 0, 0}};
  out.body_contacts = std::move(hits.per_body);
  out.outward_normal = near.outward_normal;
  return out;
}

}  // namespace argil
