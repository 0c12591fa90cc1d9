#pragma once
// The haptic tick (docs/deformation.md): one call per device sample that moves
// the tool proxy, collides it with every body, applies contact and friction
// forces to the deformable bodies, steps them, and returns the
// force to render on the device.
//
// Deterministic: no clock, no threads, no global state; the same bodies, tool
// and device samples give bit-identical results.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <memory>
#include <optional>
#include <variant>
#include <vector>

#include "argil/core/collision/contact.hpp"
#include "argil/core/deform/deformable_body.hpp"
#include "argil/core/deform/edge_joint.hpp"
#include "argil/core/deform/material.hpp"
#include "argil/core/geometry/pose.hpp"
#include "argil/core/geometry/trim_region.hpp"
#include "argil/core/haptic/device_sample.hpp"
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

/// The tool proxy after a tick: where the tool is (X_WT), not where the hand is.
struct ProxyState {
  Pose X_WT;
  Eigen::Vector3d v_WT = Eigen::Vector3d::Zero();  // velocity of T's origin in W [mm/s]
  bool in_contact = false;
  bool stuck = false;  // held by static friction this tick
  /// The contacts the tick ended with: their mean outward normal (zero
  /// without contacts) and the friction coefficient of the first body they
  /// touch (-1 without). The B-spline tool's next tick decides stick or slip
  /// with them (explicit friction), so it needs no query at its stick point.
  Eigen::Vector3d outward_normal = Eigen::Vector3d::Zero();
  double friction = -1.0;
  /// The deepest of those contacts [mm] (0 without): a B-spline tool stands
  /// -max_depth off the surfaces it touches, and its next tick settles from
  /// there (move_surface_tool).
  double max_depth = 0.0;
  /// How far off them the B-spline tool stood once this tick settled it
  /// [mm], measured from where they were when the last tick ended (negative
  /// when it settled past that; none when friction did not decide the tick:
  /// it did not stick or slip into contact): the next tick's max_depth tells
  /// how far the surfaces drew away since.
  std::optional<double> settled_gap;
};

struct [[nodiscard]] TickResult {
  /// Not ok when the tick did not run: an invalid dt, a collision query that
  /// failed (its status, naming the request and the limit) or a deformable
  /// body that could not step. The proxy then keeps its state from the last
  /// good tick (`proxy` repeats it) and no force is rendered.
  Status status;
  /// Force to render on the device [N]: the coupling pulls the hand towards the
  /// proxy; clamped to CouplingOptions::max_force.
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
  /// The B-spline tool's collision queries this tick, one per body queried
  /// (SurfaceToolProxy::queries): contact queries, placed or swept, and
  /// yes/no crossing tests. Zero for the sphere tool.
  int tool_contact_queries = 0;
  int tool_crossing_tests = 0;
  ProxyState proxy;
  /// One entry per body: its contacts at the proxy pose.
  std::vector<std::vector<Contact>> body_contacts;
};

struct WorldOptions {
  /// eps [mm]: collision tolerance; the proxy never sinks deeper.
  double tolerance = 0.01;
  CouplingOptions coupling;
  int max_contacts = 64;  // per body and tick
  /// Bodies out of the tool's reach this tick are left out of the proxy's
  /// queries (body_sleep.cpp); the results are the same to the last bit.
  bool cull = true;
  /// A deformable body out of the tool's reach that has settled sleeps (is
  /// not stepped) until the tool comes within reach (body_sleep.cpp).
  /// False, with cull false: every body is queried and stepped every tick
  /// (the reference tests and benchmarks compare against).
  bool sleep = true;
  /// Deformable bodies solve only a window of control points around the
  /// tool's contacts (DeformableBody::set_local_solves); false: the whole
  /// net every tick (the reference the local-solve tests compare against).
  bool local_solves = true;
};

/// A deformable body out of the tool's reach sleeps once every control point
/// is within this fraction of eps of its rest position and moved less than
/// it over the last tick.
inline constexpr double kSleepFraction = 1e-2;

/// Bodies (deformable or rigid) and one tool.
class HapticWorld {
 public:
  /// Validates the options and the tool (radius >= 0, a valid tool surface).
  static Result<HapticWorld> create(const ToolShape& tool, const WorldOptions& options);
  /// Gives the device another tool, between strokes only (failed_precondition
  /// while engaged: a released tool touches nothing, so the bodies need not
  /// know). Checked as create() checks its tool; on failure the old one stays.
  Status set_tool(const ToolShape& tool);

  /// Adds a deformable body; returns its index. `friction` is the Coulomb
  /// coefficient mu [-] of the world's tool against this body, in [0,
  /// kMaxFriction]: friction belongs to the tool-body pair, so it is given
  /// here and nowhere else (not in Material). Fails when mu is out of range or
  /// the world's tolerance is outside the documented range for the surface
  /// (check_request()).
  Result<int> add_deformable(const BSplineSurface& surface, const Material& material,
                             const BoundaryConditions& conditions, double friction);
  /// Adds a rigid body (collides, never deforms); `friction` as for add_deformable.
  Result<int> add_rigid(const BSplineSurface& surface, double friction);

  /// Gives body `body` its trims: only (u, v) inside `region` is material.
  /// The sphere and point tool then touch the body only inside the region or
  /// on its edge (collide_sphere and closest_point on a TrimmedSurface, for
  /// the proxy's moves and its contacts alike); the B-spline tool's contacts
  /// outside it are dropped. An empty region (every body's default) makes the
  /// whole domain material. Fails (invalid_argument, nothing changed) when
  /// `body` is not a body of this world or the region's box misses the
  /// body's domain. Trims live in (u, v), so deformation keeps them valid.
  Status set_trim(int body, TrimRegion region);
  /// Body `body`'s trims (empty: untrimmed).
  const TrimRegion& trim(int body) const;

  /// Joins bodies a and b along the edge they share, given by its curve in
  /// each one's (u, v) from the edge's start to its end (a == b: the seam of
  /// a closed face). After every tick's steps the joint's edge forces, through
  /// each body's step response, keep the faces together along the edge and
  /// turning alike about it (edge_joint.hpp); a sleeping body it moves wakes.
  /// A seam whose boundary rows of poles coincide keeps them equal to the bit.
  /// At least one body must be deformable. Returns the joint's index; fails
  /// (nothing changed) on a bad body index or curve.
  Result<int> join(int a, const BSplineCurve& pcurve_a, int b, const BSplineCurve& pcurve_b);
  int joint_count() const { return static_cast<int>(joints_.size()); }
  struct Joint {
    int a = 0, b = 0;
    EdgeJoint joint;
    /// A seam whose two boundary rows of poles coincide (a clamped closed
    /// face): the pole pairs kept equal to the bit after every correction, so
    /// the face stays exactly closed.
    std::vector<std::pair<Eigen::Index, Eigen::Index>> welded;
  };
  const Joint& joint(int k) const { return joints_[static_cast<std::size_t>(k)]; }

  /// One tick of dt [s] with the device at `device.X_WD` (its tick and time
  /// are not read: the world keeps no clock).
  ///  1. The proxy moves from its last pose towards the device (god-object,
  ///     never sinking more than eps, never passing through a surface).
  ///  2. Friction: while in contact the proxy stays at its stick point unless
  ///     the coupling's tangential pull exceeds mu N; then it slides until the
  ///     pull is mu N (contact_response.hpp).
  ///  3. Contacts of the proxy with every body (collide); the coupling force
  ///     F = k (p_WD - p_WT) + b (v_WD - v_WT) is shared among them
  ///     (contact_shares), solved backwards in time against the bodies'
  ///     compliance (implicit_coupling_force), clamped, and applied through
  ///     load patterns through the basis (contact_load_pattern).
  ///  4. Every deformable body steps (DeformableBody): its control points
  ///     move; one out of the tool's reach that has settled sleeps instead
  ///     (WorldOptions::sleep).
  ///  Strategies: sphere_tool_step.cpp (god-object sphere), surface_tool_step.cpp
  ///  (B-spline tool, conservative advancement).
  TickResult step(const DeviceSample& device, double dt);

  int body_count() const { return static_cast<int>(bodies_.size()); }
  bool is_rigid(int body) const { return !bodies_[static_cast<std::size_t>(body)].deformable; }
  /// The deformable body, or nullptr for a rigid one.
  const DeformableBody* deformable(int body) const;
  const SurfaceHierarchy& hierarchy(int body) const;
  const BSplineSurface& surface(int body) const { return hierarchy(body).surface(); }
  /// Coulomb coefficient of the tool against `body` [-].
  double friction(int body) const { return bodies_[static_cast<std::size_t>(body)].friction; }
  /// Largest node count of body `body`'s lazy hierarchy (SurfaceHierarchy::set_node_budget).
  void set_node_budget(int body, std::size_t nodes);
  const ProxyState& proxy() const { return proxy_; }
  /// Whether body `body` sleeps: settled, out of the tool's reach, not stepped
  /// (always false for a rigid body, which never steps).
  bool asleep(int body) const { return bodies_[static_cast<std::size_t>(body)].asleep; }
  const WorldOptions& options() const { return options_; }

 private:
  struct Body {
    std::optional<DeformableBody> deformable;
    std::optional<SurfaceHierarchy> rigid;
    double friction = 0.0;
    /// The force it carried last tick [N]: sets the sphere's contact disc.
    double pressing_force = 0.0;
    /// Box of the control points as they are now: encloses the surface.
    Box3 bound;
    bool asleep = false;
    bool in_reach = true;  // last tick
    /// Forces its joints apply to its poles [N] (empty: none yet), added to
    /// every step's load so a held edge does not spring open again.
    ControlNet joint_force;
    std::vector<int> joints;  // joining it to a face (or to itself)
  };
  Status install_tool(const ToolShape& tool);
  /// The proxy's move this tick (steps 1-2) and its contacts with every body.
  struct [[nodiscard]] ProxyMove {
    Status status;
    ProxyState next;  // v_WT, in_contact, outward_normal and friction are filled in by step()
    std::vector<std::vector<Contact>> body_contacts;
    /// Unit normal from the surfaces towards the proxy (zero without contacts).
    Eigen::Vector3d outward_normal = Eigen::Vector3d::Zero();
  };
  /// The tool load on the bodies and the force on the device (steps 3-4).
  struct [[nodiscard]] Coupling {
    Status status;
    Eigen::Vector3d force = Eigen::Vector3d::Zero();       // on the device [N]
    Eigen::Vector3d body_force = Eigen::Vector3d::Zero();  // on the bodies [N]
    bool clamped = false;
  };
  HapticWorld() = default;
  /// Every body's hierarchy; null where `reach` is 0 (the proxies skip it).
  std::vector<const SurfaceHierarchy*> surfaces(const std::vector<char>& reach) const;
  /// Every body with its trims (body_trim.cpp); a null hierarchy where `reach` is 0.
  std::vector<TrimmedSurface> trimmed_surfaces(const std::vector<char>& reach) const;
  /// Which bodies the tool can reach this tick from `previous` towards the
  /// device (body_sleep.cpp), whatever the options: the world wakes and
  /// queries only these with WorldOptions::sleep or cull, and anticipates
  /// windows on these in any case (so the solution does not depend on them).
  /// `extra` [mm] widens the reach (anticipation looks one tool reach further).
  std::vector<char> within_reach(const ProxyState& previous, const DeviceSample& device,
                                 double extra = 0.0) const;
  /// Bodies resting in reach of the tool at p_WT prepare the window its
  /// closest point would need (DeformableBody::anticipate).
  void anticipate(const std::vector<char>& near, const Eigen::Vector3d& p_WT, double dt);
  /// Wakes the bodies in reach; a sphere proxy records its side of a body
  /// that comes back into reach afresh.
  void wake(const std::vector<char>& reach);
  /// After the bodies stepped: the largest motion, the bounds, and which
  /// bodies out of reach fall asleep.
  void settle(const std::vector<char>& reach);
  /// The world's tolerance checked against the documented range for a body.
  Status check_tolerance(const SurfaceHierarchy& surface) const;
  int add_body(Body body);
  /// Steps every deformable body without tool load.
  Status relax(double dt);
  /// Restores every joint whose bodies moved this tick of dt [s] (after they
  /// stepped); fails only when a body's step matrix cannot be factorised.
  /// Returns how many joints it had to prepare.
  Result<int> enforce_joints(double dt);
  /// Gives joint `j` its bodies' step responses at dt.
  Status prepare_joint(Joint& j, double dt);
  /// Prepares the joint nearest the tool at p_WT, of those of a `near` body
  /// not yet prepared for dt whose edge is within one tool reach of the
  /// tool's and the body's influence length beyond, and whose poles a step
  /// under the tool can move. Called at the end of a tick out of contact that
  /// prepared no joint. A failure is left for enforce_joints to report when
  /// the joint is needed.
  void prepare_joint_ahead(const std::vector<char>& near, const Eigen::Vector3d& p_WT, double dt);
  /// Moves each welded pole pair of seam `j` to its mean (to the held one's
  /// place when one is held).
  void weld_seam(const Joint& j);
  ProxyMove move_sphere(const ProxyState& previous, const DeviceSample& device,
                        const std::vector<char>& reach);
  ProxyMove move_surface_tool(const ProxyState& previous, const DeviceSample& device,
                              const std::vector<char>& reach);
  /// Shares `spring` (the coupling force on the device side, pressing when
  /// `pressing`) among the bodies by `weight`, solves it backwards in time and
  /// steps every deformable body that is awake.
  Coupling step_bodies(const std::vector<std::vector<Contact>>& body_contacts,
                       const std::vector<double>& weight, const Eigen::Vector3d& spring,
                       bool pressing, double dt);

  WorldOptions options_;
  std::unique_ptr<OperatorCache> cache_;
  std::vector<Body> bodies_;
  std::vector<Joint> joints_;
  /// Per joint, what prepare_joint_ahead knows of it: the poles it loads
  /// on each side, its edge's sample points at rest [mm] and half their
  /// largest spacing, the tool's distance to the edge (less that half
  /// spacing) when last measured and where the tool was then, and whether its
  /// preparation failed (it is then left for when it is needed).
  struct EdgeAhead {
    std::array<std::vector<Eigen::Index>, 2> poles;
    std::vector<Eigen::Vector3d> points;
    double half_spacing = 0.0;
    double distance = -1.0;  // negative: not measured
    Eigen::Vector3d from = Eigen::Vector3d::Zero();
    bool failed = false;
  };
  std::vector<EdgeAhead> edges_ahead_;
  std::vector<TrimRegion> trims_;  // per body; bodies past its end are untrimmed
  TrimRegion untrimmed_;
  std::optional<SphereProxy> sphere_;
  std::optional<SurfaceToolProxy> surface_tool_;
  ProxyState proxy_;
  /// Radius about the tool frame's origin that holds the tool at any pose,
  /// plus how far a B-spline tool's push-out may move it [mm].
  double tool_reach_ = 0.0;
  /// Largest control-point move of any body last tick [mm]: how far a surface
  /// can have pushed into the proxy since.
  double motion_ = 0.0;
  bool engaged_ = false;
  Eigen::Vector3d last_device_ = Eigen::Vector3d::Zero();
};

}  // namespace argil
