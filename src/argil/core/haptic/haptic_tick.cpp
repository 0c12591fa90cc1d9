#include "argil/core/haptic/haptic_tick.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "argil/core/base/number_text.hpp"

#include "argil/core/collision/implicit_contact.hpp"
#include "argil/core/deform/contact_response.hpp"
#include "argil/core/geometry/implicit_tool.hpp"

namespace argil {

Result<HapticWorld> HapticWorld::create(const ToolShape& tool, const WorldOptions& options) {
  if (Status s = validate(options.coupling); !s.ok()) return s;
  if (!(options.tolerance > 0.0 && std::isfinite(options.tolerance))) {
    return Status::error(
        StatusCode::invalid_argument,
        "world.tolerance " + number_text(options.tolerance) + " mm must be positive and finite");
  }
  if (options.max_contacts < 1)
    return Status::error(StatusCode::invalid_argument, "world.max_contacts must be at least 1");
  HapticWorld world;
  world.options_ = options;
  world.cache_ = std::make_unique<OperatorCache>();
  if (const auto* sphere = std::get_if<SphereToolShape>(&tool)) {
    if (!(sphere->radius >= 0.0 && std::isfinite(sphere->radius))) {
      return Status::error(
          StatusCode::invalid_argument,
          "tool.radius " + number_text(sphere->radius) + " mm must be finite and at least 0 mm");
    }
    world.sphere_.emplace(sphere->radius, options.tolerance);
  } else {
    Result<SurfaceToolProxy> proxy = SurfaceToolProxy::create(
        std::get<SurfaceToolShape>(tool).surface, options.tolerance, *world.cache_);
    if (!proxy.ok()) {
      Status s = proxy.status();
      s.message = "tool surface: " + s.message;
      return s;
    }
    world.surface_tool_.emplace(std::move(proxy).value());
  }
  return world;
}

Result<int> HapticWorld::add_deformable(const BSplineSurface& surface, const Material& material,
                                        const BoundaryConditions& conditions) {
  Result<DeformableBody> body = DeformableBody::create(surface, material, conditions, *cache_);
  if (!body.ok()) return body.status();
  if (Status s = check_tolerance(body.value().hierarchy()); !s.ok()) return s;
  Body b;
  b.friction = material.friction;
  b.deformable.emplace(std::move(body).value());
  bodies_.push_back(std::move(b));
  return body_count() - 1;
}

Status HapticWorld::check_tolerance(SurfaceHierarchy& surface) const {
  // The proxies query at eps and at eps / 4: both must be in the documented
  // range for this surface, or every contact query of a tick would fail.
  for (const double tolerance : {options_.tolerance, 0.25 * options_.tolerance}) {
    const Status s = check_request({.tolerance = tolerance}, surface);
    if (!s.ok()) {
      return Status::error(s.code, "body " + std::to_string(body_count()) + ": " + s.message);
    }
  }
  return Status::success();
}

Result<int> HapticWorld::add_rigid(const BSplineSurface& surface, double friction) {
  if (const Interval range{0.0, kMaterialRange.friction_max}; !range.contains(friction)) {
    return Status::error(StatusCode::invalid_argument,
                         "rigid body friction " + out_of_interval_text(friction, range, ""));
  }
  Result<SurfaceHierarchy> h = SurfaceHierarchy::build(surface, *cache_);
  if (!h.ok()) return h.status();
  if (Status s = check_tolerance(h.value()); !s.ok()) return s;
  Body b;
  b.friction = friction;
  b.rigid.emplace(std::move(h).value());
  bodies_.push_back(std::move(b));
  return body_count() - 1;
}

const DeformableBody* HapticWorld::deformable(int body) const {
  const Body& b = bodies_[static_cast<std::size_t>(body)];
  return b.deformable ? &*b.deformable : nullptr;
}

SurfaceHierarchy& HapticWorld::hierarchy(int body) {
  Body& b = bodies_[static_cast<std::size_t>(body)];
  return b.deformable ? b.deformable->hierarchy() : *b.rigid;
}

const BSplineSurface& HapticWorld::surface(int body) { return hierarchy(body).surface(); }

std::vector<SurfaceHierarchy*> HapticWorld::surfaces() {
  std::vector<SurfaceHierarchy*> out;
  for (int b = 0; b < body_count(); ++b) out.push_back(&hierarchy(b));
  return out;
}

Status HapticWorld::relax(double dt) {
  for (Body& b : bodies_)
    if (b.deformable)
      if (Status s = b.deformable->step(dt); !s.ok()) return s;
  return Status::success();
}

TickResult HapticWorld::step(const DevicePose& device, double dt) {
  TickResult r;
  r.body_contacts.resize(bodies_.size());
  if (const Interval range{0.0, kMaxTimeStep, IntervalEnds::open_low}; !range.contains(dt)) {
    r.status = Status::error(StatusCode::invalid_argument,
                             "time step dt " + out_of_interval_text(dt, range, "s"));
    r.proxy = proxy_;
    return r;
  }
  const CouplingParams& coupling = options_.coupling;
  const double eps = options_.tolerance;
  const Eigen::Vector3d device_velocity =
      engaged_ ? Eigen::Vector3d((device.position - last_device_) / dt) : Eigen::Vector3d::Zero();
  last_device_ = device.position;
  if (!device.engaged) {
    engaged_ = false;
    proxy_ = {device.position, device.orientation, Eigen::Vector3d::Zero(), false, false};
    r.status = relax(dt);
    r.proxy = proxy_;
    return r;
  }
  ToolState previous = proxy_;
  if (!engaged_) {  // engaging: the proxy starts at the device
    previous = {device.position, device.orientation, Eigen::Vector3d::Zero(), false, false};
    if (sphere_) sphere_.emplace(sphere_->radius(), eps);  // forget the sides
  }
  engaged_ = true;
  const std::vector<SurfaceHierarchy*> surfs = surfaces();
  const double k = coupling.stiffness;

  // 1-2. Proxy: frictionless target, then stick or slip from the last pose.
  ToolState next;
  next.orientation = device.orientation;
  Eigen::Vector3d outward = Eigen::Vector3d::Zero();
  if (sphere_) {
    next.position = sphere_->move(surfs, previous.position, device.position);
    if (previous.in_contact) {
      const Eigen::Vector3d stick = sphere_->project(surfs, previous.position);
      const ProxyContact at = sphere_->nearest(surfs, stick);
      if (at.body >= 0 && at.clearance <= eps) {
        const FrictionOutcome fr =
            coulomb_friction(k * (device.position - stick), at.outward_normal,
                             bodies_[static_cast<std::size_t>(at.body)].friction, k);
        if (fr.normal_force > 0.0) {
          next.stuck = fr.stick;
          next.position = fr.stick ? stick : sphere_->move(surfs, stick, stick + fr.slide);
        }
      }
    }
    const auto tool = make_sphere(next.position, sphere_->radius());
    for (std::size_t b = 0; b < bodies_.size(); ++b) {
      CollisionResult hit =
          collide(*surfs[b], *tool, {.tolerance = eps, .max_contacts = options_.max_contacts});
      if (!hit.status.ok() && r.status.ok()) r.status = hit.status;
      r.body_contacts[b] = std::move(hit.contacts);
    }
    outward = sphere_->nearest(surfs, next.position).outward_normal;
  } else {
    const ToolPose target{device.position, device.orientation};
    ToolPose pose = surface_tool_->move(surfs, {previous.position, previous.orientation}, target);
    if (previous.in_contact) {
      const ToolPose stick{previous.position, device.orientation};
      const ToolContacts at = surface_tool_->contacts(surfs, stick);
      double mu = -1.0;
      for (std::size_t b = 0; b < bodies_.size() && mu < 0.0; ++b)
        if (!at.per_surface[b].empty()) mu = bodies_[b].friction;
      if (!at.crosses && mu >= 0.0) {
        const FrictionOutcome fr =
            coulomb_friction(k * (device.position - stick.position), at.outward_normal, mu, k);
        if (fr.normal_force > 0.0) {
          next.stuck = fr.stick;
          if (fr.stick) {
            pose = stick;
          } else {
            ToolPose slid = stick;
            slid.position += fr.slide;
            pose = surface_tool_->move(surfs, stick, slid);
          }
        }
      }
    }
    next.position = pose.position;
    ToolContacts at = surface_tool_->contacts(surfs, pose);
    r.body_contacts = std::move(at.per_surface);
    outward = at.outward_normal;
  }
  next.velocity = (next.position - previous.position) / dt;

  // 3. Contacts and the coupling force.
  double total_weight = 0.0;
  std::vector<double> weight(bodies_.size(), 0.0);
  r.max_depth = -std::numeric_limits<double>::infinity();
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    for (const Contact& c : r.body_contacts[b]) {
      weight[b] += std::max(c.depth + eps, 1e-3 * eps);
      r.max_depth = std::max(r.max_depth, c.depth);
      r.regions = std::max(r.regions, c.region + 1);
    }
    r.contacts += static_cast<int>(r.body_contacts[b].size());
    total_weight += weight[b];
  }
  if (r.contacts == 0) r.max_depth = 0.0;
  next.in_contact = r.contacts > 0;
  const Eigen::Vector3d spring =
      k * (device.position - next.position) + coupling.damping * (device_velocity - next.velocity);
  const bool pressing = next.in_contact && spring.dot(outward) < 0.0;

  // 4. Step the bodies, the tool load solved backwards in time.
  std::vector<LoadPreview> previews(bodies_.size());
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    if (!bodies_[b].deformable) continue;
    DeformableBody& body = *bodies_[b].deformable;
    Eigen::VectorXd pattern;
    if (pressing && !r.body_contacts[b].empty())
      pattern = contact_load_pattern(body.surface(), body.operators(), r.body_contacts[b],
                                     contact_shares(r.body_contacts[b], eps));
    Result<LoadPreview> p = body.begin_step(dt, {}, pattern);
    if (!p.ok()) {
      r.status = p.status();
      r.proxy = proxy_;
      return r;
    }
    previews[b] = p.value();
  }
  Eigen::Vector3d load = Eigen::Vector3d::Zero();
  if (pressing && spring.norm() > 0.0) {
    const Eigen::Vector3d direction = spring.normalized();
    double free_motion = 0.0, compliance = 0.0;
    for (std::size_t b = 0; b < bodies_.size(); ++b) {
      const double share = weight[b] / total_weight;
      free_motion += share * direction.dot(previews[b].free_motion);
      compliance += share * share * previews[b].compliance;
    }
    load =
        clamp_force(implicit_coupling_force(spring.norm(), k, free_motion, compliance) * direction,
                    coupling.max_force, r.clamped);
    r.body_force = load;
    r.force = -load;
  } else {
    r.force = clamp_force(-spring, coupling.max_force, r.clamped);
  }
  for (std::size_t b = 0; b < bodies_.size(); ++b)
    if (bodies_[b].deformable)
      bodies_[b].deformable->finish_step(total_weight > 0.0
                                             ? Eigen::Vector3d(load * (weight[b] / total_weight))
                                             : Eigen::Vector3d::Zero());
  proxy_ = next;
  r.proxy = next;
  return r;
}

}  // namespace argil
