#pragma once
// The haptic tick (docs/deformation.md): one call per device sample that moves
// the tool proxy, collides it with every body, applies contact and friction
// forces to the deformable bodies, steps and refits them, and returns the
// force to render on the device.
//
// Deterministic: no clock, no threads, no global state; the same bodies, tool
// and device samples give bit-identical results.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <variant>
#include <vector>

#include "argil/core/collision/contact.hpp"
#include "argil/core/deform/deformable_body.hpp"
#include "argil/core/deform/material.hpp"
#include "argil/core/haptic/sphere_proxy.hpp"
#include "argil/core/haptic/surface_tool_proxy.hpp"
#include "argil/core/haptic/virtual_coupling.hpp"

namespace argil {

/// A sphere tool of `radius` [mm] centred on the tool frame origin (radius 0:
/// a point tool).
struct SphereToolShape {
  double radius = 5.0;
};
/// A rigid B-spline tool surface given in the tool frame T [mm].
struct SurfaceToolShape {
  BSplineSurface surface;
};
using ToolShape = std::variant<SphereToolShape, SurfaceToolShape>;

/// One device sample: the pose X_WD of the device handle [mm] and whether the
/// tool is engaged (disengaged: the proxy follows the device and touches nothing).
struct DevicePose {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  bool engaged = true;
};

/// The proxy after a tick.
struct ToolState {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // p_WT [mm]
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  // [mm/s]
  bool in_contact = false;
  bool stuck = false;  // held by static friction this tick
};

struct TickResult {
  /// Force to render on the device [N]: the coupling pulls the hand towards the
  /// proxy; clamped to CouplingParams::max_force.
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  /// Force the tool applies to the bodies this tick [N] (equal and opposite
  /// to `force` while in contact, zero otherwise).
  Eigen::Vector3d body_force = Eigen::Vector3d::Zero();
  int contacts = 0;
  int regions = 0;
  /// Deepest contact at the proxy pose, against the bodies as they were before
  /// this tick's deformation [mm] (at most eps for a sphere tool).
  double max_depth = 0.0;
  bool clamped = false;
  ToolState proxy;
  /// One entry per body: its contacts at the proxy pose.
  std::vector<std::vector<Contact>> body_contacts;
  /// Not ok when a deformable body could not step (invalid dt).
  Status status;
};

struct WorldOptions {
  /// eps [mm]: collision tolerance; the proxy never sinks deeper.
  double tolerance = 0.01;
  CouplingParams coupling;
  int max_contacts = 64;  // per body and tick
};

/// Bodies (deformable or rigid) and one tool.
class HapticWorld {
 public:
  /// Validates the options and the tool (radius >= 0, a valid tool surface).
  static Result<HapticWorld> create(const ToolShape& tool, const WorldOptions& options);

  /// Adds a deformable body; returns its index. Fails when the world's
  /// tolerance is outside the documented range for it (check_request()).
  Result<int> add_deformable(const BSplineSurface& surface, const Material& material,
                             const BoundaryConditions& conditions);
  /// Adds a rigid body (collides, never deforms) with tool friction mu in [0, 10].
  Result<int> add_rigid(const BSplineSurface& surface, double friction);

  /// One tick of dt [s] with the device at `device`.
  ///  1. The proxy moves from its last pose towards the device (god-object,
  ///     never sinking more than eps, never passing through a surface).
  ///  2. Friction: while in contact the proxy stays at its stick point unless
  ///     the coupling's tangential pull exceeds mu N; then it slides until the
  ///     pull is mu N (contact_response.hpp).
  ///  3. Contacts of the proxy with every body (collide); the coupling force
  ///     F = k (device - proxy) + b (v_device - v_proxy) is shared among them
  ///     (contact_shares), solved backwards in time against the bodies'
  ///     compliance (implicit_coupling_force), clamped, and applied through
  ///     exact node load patterns (contact_load_pattern).
  ///  4. Every deformable body steps (DeformableBody) and refits its surface.
  TickResult step(const DevicePose& device, double dt);

  int body_count() const { return static_cast<int>(bodies_.size()); }
  bool is_rigid(int body) const { return !bodies_[static_cast<std::size_t>(body)].deformable; }
  /// The deformable body, or nullptr for a rigid one.
  const DeformableBody* deformable(int body) const;
  SurfaceHierarchy& hierarchy(int body);
  const BSplineSurface& surface(int body);
  const ToolState& proxy() const { return proxy_; }
  const WorldOptions& options() const { return options_; }

 private:
  struct Body {
    std::optional<DeformableBody> deformable;
    std::optional<SurfaceHierarchy> rigid;
    double friction = 0.0;
  };
  HapticWorld() = default;
  std::vector<SurfaceHierarchy*> surfaces();
  /// The world's tolerance checked against the documented range for a body.
  Status check_tolerance(SurfaceHierarchy& surface) const;
  /// Steps every deformable body without tool load.
  Status relax(double dt);

  WorldOptions options_;
  std::unique_ptr<OperatorCache> cache_;
  std::vector<Body> bodies_;
  std::optional<SphereProxy> sphere_;
  std::optional<SurfaceToolProxy> surface_tool_;
  ToolState proxy_;
  bool engaged_ = false;
  Eigen::Vector3d last_device_ = Eigen::Vector3d::Zero();
};

}  // namespace argil
