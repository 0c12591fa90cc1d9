#include "argil/core/haptic/haptic_tick.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "argil/core/base/number_text.hpp"
#include "argil/core/deform/contact_footprint.hpp"
#include "argil/core/deform/contact_response.hpp"

namespace argil {

namespace {

Status check_options(const WorldOptions& options) {
  if (Status s = validate(options.coupling); !s.ok()) return s;
  if (!(options.tolerance > 0.0 && std::isfinite(options.tolerance))) {
    return Status::error(
        StatusCode::invalid_argument,
        "world.tolerance " + number_text(options.tolerance) + " mm must be positive and finite");
  }
  if (options.max_contacts < 1)
    return Status::error(
        StatusCode::invalid_argument,
        "world.max_contacts must be at least 1, got " + std::to_string(options.max_contacts));
  return Status::success();
}

Status check_friction(double friction) {
  if (const Interval range{0.0, kMaxFriction}; !range.contains(friction)) {
    return Status::error(StatusCode::invalid_argument,
                         "body friction " + out_of_interval_text(friction, range, ""));
  }
  return Status::success();
}

/// How the contacts of one tick are spread over the bodies.
struct ContactSummary {
  std::vector<double> weight;  // per body: sum of max(depth + eps, 1e-3 eps)
  int contacts = 0;
  int regions = 0;
  double max_depth = 0.0;  // [mm], 0 without contacts
};

ContactSummary summarize(const std::vector<std::vector<Contact>>& body_contacts, double eps) {
  ContactSummary s;
  s.weight.assign(body_contacts.size(), 0.0);
  s.max_depth = -std::numeric_limits<double>::infinity();
  for (std::size_t b = 0; b < body_contacts.size(); ++b) {
    for (const Contact& c : body_contacts[b]) {
      s.weight[b] += std::max(c.depth + eps, 1e-3 * eps);
      s.max_depth = std::max(s.max_depth, c.depth);
      s.regions = std::max(s.regions, c.region + 1);
    }
    s.contacts += static_cast<int>(body_contacts[b].size());
  }
  if (s.contacts == 0) s.max_depth = 0.0;
  return s;
}

ProxyState at_device(const DeviceSample& device) {
  ProxyState s;
  s.X_WT = device.X_WD;
  return s;
}

}  // namespace

Result<HapticWorld> HapticWorld::create(const ToolShape& tool, const WorldOptions& options) {
  if (Status s = check_options(options); !s.ok()) return s;
  HapticWorld world;
  world.options_ = options;
  world.cache_ = std::make_unique<OperatorCache>();
  if (Status s = world.install_tool(tool); !s.ok()) return s;
  return world;
}

Status HapticWorld::set_tool(const ToolShape& tool) {
  if (engaged_) {
    return Status::error(StatusCode::failed_precondition,
                         "the tool can only change while released (a stroke is in progress)");
  }
  return install_tool(tool);
}

Status HapticWorld::install_tool(const ToolShape& tool) {
  if (const auto* sphere = std::get_if<SphereToolShape>(&tool)) {
    if (!(sphere->radius >= 0.0 && std::isfinite(sphere->radius))) {
      return Status::error(
          StatusCode::invalid_argument,
          "tool.radius " + number_text(sphere->radius) + " mm must be finite and at least 0 mm");
    }
    surface_tool_.reset();
    sphere_.emplace(sphere->radius, options_.tolerance);
    tool_reach_ = sphere->radius;
    return Status::success();
  }
  Result<SurfaceToolProxy> proxy = SurfaceToolProxy::create(
      std::get<SurfaceToolShape>(tool).surface, options_.tolerance, *cache_, options_.max_contacts);
  if (!proxy.ok()) {
    Status s = proxy.status();
    s.message = "tool surface: " + s.message;
    return s;
  }
  sphere_.reset();
  surface_tool_.emplace(std::move(proxy).value());
  // Its push-out out of a surface that moved into it goes up to 4 tool sizes.
  const ControlNet& points = std::get<SurfaceToolShape>(tool).surface.control_points;
  tool_reach_ = points.rowwise().norm().maxCoeff() + 4.0 * surface_tool_->size();
  return Status::success();
}

Result<int> HapticWorld::add_deformable(const BSplineSurface& surface, const Material& material,
                                        const BoundaryConditions& conditions, double friction) {
  if (Status s = check_friction(friction); !s.ok()) return s;
  Result<DeformableBody> body = DeformableBody::create(surface, material, conditions, *cache_);
  if (!body.ok()) return body.status();
  if (Status s = check_tolerance(body.value().hierarchy()); !s.ok()) return s;
  Body b;
  b.friction = friction;
  b.deformable.emplace(std::move(body).value());
  b.deformable->set_local_solves(options_.local_solves);
  // A new body is at rest: it sleeps until the tool comes within reach.
  b.asleep = options_.sleep;
  return add_body(std::move(b));
}

Result<int> HapticWorld::add_rigid(const BSplineSurface& surface, double friction) {
  if (Status s = check_friction(friction); !s.ok()) return s;
  Result<SurfaceHierarchy> h = SurfaceHierarchy::build(surface, *cache_);
  if (!h.ok()) return h.status();
  if (Status s = check_tolerance(h.value()); !s.ok()) return s;
  Body b;
  b.friction = friction;
  b.rigid.emplace(std::move(h).value());
  return add_body(std::move(b));
}

int HapticWorld::add_body(Body body) {
  body.bound =
      control_point_box(body.deformable ? body.deformable->surface() : body.rigid->surface());
  bodies_.push_back(std::move(body));
  return body_count() - 1;
}

Status HapticWorld::check_tolerance(const SurfaceHierarchy& surface) const {
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

const DeformableBody* HapticWorld::deformable(int body) const {
  const Body& b = bodies_[static_cast<std::size_t>(body)];
  return b.deformable ? &*b.deformable : nullptr;
}

const SurfaceHierarchy& HapticWorld::hierarchy(int body) const {
  const Body& b = bodies_[static_cast<std::size_t>(body)];
  return b.deformable ? b.deformable->hierarchy() : *b.rigid;
}

void HapticWorld::set_node_budget(int body, std::size_t nodes) {
  Body& b = bodies_[static_cast<std::size_t>(body)];
  if (b.deformable) {
    b.deformable->set_node_budget(nodes);
  } else {
    b.rigid->set_node_budget(nodes);
  }
}

std::vector<const SurfaceHierarchy*> HapticWorld::surfaces(const std::vector<char>& reach) const {
  std::vector<const SurfaceHierarchy*> out;
  for (int b = 0; b < body_count(); ++b)
    out.push_back(reach[static_cast<std::size_t>(b)] ? &hierarchy(b) : nullptr);
  return out;
}

Status HapticWorld::relax(double dt) {
  for (Body& b : bodies_) {
    if (!b.deformable) continue;
    // A sleeping body goes on preparing its window, as it would awake.
    Status s = b.asleep ? b.deformable->prepare_window(dt) : b.deformable->step(dt, b.joint_force);
    if (!s.ok()) return s;
  }
  if (Result<int> joints = enforce_joints(dt); !joints.ok()) return joints.status();
  // No tool: every body is out of reach.
  settle(std::vector<char>(bodies_.size(), 0));
  return Status::success();
}

TickResult HapticWorld::step(const DeviceSample& device, double dt) {
  TickResult r;
  r.body_contacts.resize(bodies_.size());
  r.proxy = proxy_;
  if (const Interval range{0.0, kMaxTimeStep, IntervalEnds::open_low}; !range.contains(dt)) {
    r.status = Status::error(StatusCode::invalid_argument,
                             "time step dt " + out_of_interval_text(dt, range, "s"));
    return r;
  }
  const Eigen::Vector3d v_WD =
      engaged_ ? Eigen::Vector3d((device.X_WD.p - last_device_) / dt) : Eigen::Vector3d::Zero();
  last_device_ = device.X_WD.p;
  if (!device.engaged) {
    engaged_ = false;
    proxy_ = at_device(device);
    r.status = relax(dt);
    r.proxy = proxy_;
    return r;
  }
  ProxyState previous = proxy_;
  if (!engaged_) {  // engaging: the proxy starts at the device
    previous = at_device(device);
    if (sphere_) sphere_.emplace(sphere_->radius(), options_.tolerance);  // forget the sides
  }
  engaged_ = true;
  const std::vector<char> near = within_reach(previous, device);
  const std::vector<char> reach =
      options_.cull || options_.sleep ? near : std::vector<char>(bodies_.size(), 1);
  wake(reach);
  // Windows are prepared from one tool reach further out than contact can come.
  const std::vector<char> around = within_reach(previous, device, tool_reach_);
  anticipate(around, previous.X_WT.p, dt);

  // 1-2. Proxy: frictionless target, then stick or slip from the last pose.
  const std::vector<char> queried = options_.cull ? reach : std::vector<char>(reach.size(), 1);
  const SurfaceToolProxy::QueryCounts before =
      surface_tool_ ? surface_tool_->queries() : SurfaceToolProxy::QueryCounts{};
  ProxyMove move = sphere_ ? move_sphere(previous, device, queried)
                           : move_surface_tool(previous, device, queried);
  if (surface_tool_) {
    r.tool_contact_queries = static_cast<int>(surface_tool_->queries().contacts - before.contacts);
    r.tool_crossing_tests = static_cast<int>(surface_tool_->queries().crossings - before.crossings);
  }
  if (!move.status.ok()) {
    r.status = std::move(move.status);
    return r;
  }
  ProxyState& next = move.next;
  next.v_WT = (next.X_WT.p - previous.X_WT.p) / dt;

  // 3. Contacts and the coupling force; 4. the bodies stepped under it.
  const ContactSummary summary = summarize(move.body_contacts, options_.tolerance);
  next.in_contact = summary.contacts > 0;
  next.outward_normal = move.outward_normal;
  next.max_depth = summary.max_depth;
  for (int b = 0; b < body_count() && next.friction < 0.0; ++b)
    if (!move.body_contacts[static_cast<std::size_t>(b)].empty()) next.friction = friction(b);
  const CouplingOptions& coupling = options_.coupling;
  const Eigen::Vector3d spring =
      coupling.stiffness * (device.X_WD.p - next.X_WT.p) + coupling.damping * (v_WD - next.v_WT);
  const bool pressing = next.in_contact && spring.dot(move.outward_normal) < 0.0;
  Coupling load = step_bodies(move.body_contacts, summary.weight, spring, pressing, dt);
  if (!load.status.ok()) {
    r.status = std::move(load.status);
    return r;
  }
  const Result<int> joints = enforce_joints(dt);
  if (!joints.ok()) {
    r.status = joints.status();
    return r;
  }
  settle(reach);
  // Out of contact only: in contact a joint prepared ahead costs a tick with
  // force as much as one prepared when first needed, and may never be needed.
  if (joints.value() == 0 && !next.in_contact) prepare_joint_ahead(around, next.X_WT.p, dt);
  r.force = load.force;
  r.body_force = load.body_force;
  r.clamped = load.clamped;
  r.contacts = summary.contacts;
  r.regions = summary.regions;
  r.max_depth = summary.max_depth;
  r.body_contacts = std::move(move.body_contacts);
  proxy_ = next;
  r.proxy = next;
  return r;
}

HapticWorld::Coupling HapticWorld::step_bodies(
    const std::vector<std::vector<Contact>>& body_contacts, const std::vector<double>& weight,
    const Eigen::Vector3d& spring, bool pressing, double dt) {
  const double eps = options_.tolerance;
  std::vector<LoadPreview> previews(bodies_.size());
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    if (!bodies_[b].deformable || bodies_[b].asleep) continue;
    DeformableBody& body = *bodies_[b].deformable;
    Result<LoadPreview> p = LoadPreview{};
    if (pressing && !body_contacts[b].empty()) {
      // A sphere presses over its contact disc, sized by last tick's force.
      const double disc = sphere_
                              ? sphere_contact_radius(sphere_->radius(), bodies_[b].pressing_force,
                                                      body.material().foundation_stiffness)
                              : 0.0;
      p = body.begin_step(dt, bodies_[b].joint_force,
                          footprint_pole_weights(body.surface(), body_contacts[b],
                                                 contact_shares(body_contacts[b], eps), disc,
                                                 trim(static_cast<int>(b))));
    } else {
      p = body.begin_step(dt, bodies_[b].joint_force, Eigen::VectorXd());
    }
    if (!p.ok()) return {p.status(), {0, 0, 0}, {0, 0, 0}, false};
    previews[b] = p.value();
  }
  double total_weight = 0.0;
  for (const double w : weight) total_weight += w;
  Coupling out;
  Eigen::Vector3d load = Eigen::Vector3d::Zero();
  if (pressing && spring.norm() > 0.0) {
    const Eigen::Vector3d direction = spring.normalized();
    double free_motion = 0.0, compliance = 0.0;
    for (std::size_t b = 0; b < bodies_.size(); ++b) {
      const double share = weight[b] / total_weight;
      free_motion += share * direction.dot(previews[b].free_motion);
      compliance += share * share * previews[b].compliance;
    }
    const double k = options_.coupling.stiffness;
    const ClampedForce f =
        clamp_force(implicit_coupling_force(spring.norm(), k, free_motion, compliance) * direction,
                    options_.coupling.max_force);
    load = f.force;
    out = {Status::success(), -load, load, f.clamped};
  } else {
    const ClampedForce f = clamp_force(-spring, options_.coupling.max_force);
    out = {Status::success(), f.force, {0, 0, 0}, f.clamped};
  }
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    if (!bodies_[b].deformable || bodies_[b].asleep) continue;
    const Eigen::Vector3d carried = total_weight > 0.0
                                        ? Eigen::Vector3d(load * (weight[b] / total_weight))
                                        : Eigen::Vector3d::Zero();
    bodies_[b].deformable->finish_step(carried);
    bodies_[b].pressing_force = carried.norm();
  }
  return out;
}

}  // namespace argil
