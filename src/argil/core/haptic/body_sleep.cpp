// HapticWorld's reach and sleep: which bodies the tool can touch this tick,
// and which deformable bodies out of its reach have settled and stop stepping.
#include <algorithm>

#include "argil/core/collision/implicit_contact.hpp"
#include "argil/core/haptic/haptic_tick.hpp"

namespace argil {

namespace {

double distance_to_box(const Eigen::Vector3d& p, const Box3& box) {
  return (p - p.cwiseMax(box.min).cwiseMin(box.max)).norm();
}

}  // namespace

std::vector<char> HapticWorld::within_reach(const ProxyState& previous, const DeviceSample& device,
                                            double extra) const {
  std::vector<char> reach(bodies_.size(), 1);
  // Over this tick the proxy moves from its last pose towards the device: at
  // most |p_WD - p_WT| along its path, plus how far the surfaces pushed it
  // out, which is no more than they moved into it since (motion_). The tool
  // stays within tool_reach_ of its frame's origin at any rotation; a contact
  // counts within eps and the nearest surface's normal blends those within
  // 2 eps. The travel is counted twice and eps four times: a safety margin
  // for the friction re-move from the stick point and for pushes in a wedge.
  const Eigen::Vector3d& p_WT = previous.X_WT.p;
  const double travel = (device.X_WD.p - p_WT).norm() + motion_;
  const double reach_distance = tool_reach_ + 2.0 * travel + 4.0 * options_.tolerance + extra;
  for (std::size_t b = 0; b < bodies_.size(); ++b)
    reach[b] = distance_to_box(p_WT, bodies_[b].bound) <= reach_distance ? 1 : 0;
  return reach;
}

void HapticWorld::anticipate(const std::vector<char>& near, const Eigen::Vector3d& p_WT,
                             double dt) {
  // Asleep or awake alike, so the solution does not depend on sleep: a
  // sleeping body prepares its window here, an awake one in its step.
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    Body& body = bodies_[b];
    if (!body.deformable) continue;
    DeformableBody& d = *body.deformable;
    if (near[b] && d.resting() && !d.window_planned() && d.local_solves()) {
      const ClosestPoint c = closest_point(d.hierarchy(), p_WT, {.tolerance = options_.tolerance});
      if (c.status.ok()) d.anticipate(c.uv, dt);
    }
    if (body.asleep) (void)d.prepare_window(dt);
  }
}

void HapticWorld::wake(const std::vector<char>& reach) {
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    Body& body = bodies_[b];
    if (!reach[b]) continue;
    body.asleep = false;
    // Out of reach the proxy did not watch which side of the body it is on;
    // it is farther than the reach margin from it now, where the side is
    // simply the sign of the signed distance (SphereProxy::forget_side).
    if (!body.in_reach && sphere_ && options_.cull) sphere_->forget_side(b);
  }
  for (std::size_t b = 0; b < bodies_.size(); ++b) bodies_[b].in_reach = reach[b] != 0;
}

void HapticWorld::settle(const std::vector<char>& reach) {
  const double rest = kSleepFraction * options_.tolerance;
  motion_ = 0.0;
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    Body& body = bodies_[b];
    if (!body.deformable || body.asleep) continue;
    DeformableBody& d = *body.deformable;
    motion_ = std::max(motion_, d.last_step_motion());
    // Only the poles the step solved for moved: the bound grows to hold them
    // (a cost that follows the window, not the net), and is made tight again
    // when the body falls asleep.
    const Box3 moved = d.solved_box();
    body.bound = {body.bound.min.cwiseMin(moved.min), body.bound.max.cwiseMax(moved.max)};
    // The test is on motion, not contact: a released body steps until it
    // settles, whatever the tool does.
    // A body its joints hold off its rest settles where they hold it.
    const bool settled =
        body.joint_force.rows() > 0 ? d.last_step_motion() < rest : d.settled(rest);
    if (options_.sleep && !reach[b] && settled) {
      body.asleep = true;
      d.halt();
      body.bound = control_point_box(d.surface());
    }
  }
}

}  // namespace argil
