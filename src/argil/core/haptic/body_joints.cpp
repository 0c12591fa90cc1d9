// HapticWorld's joints: faces that share an edge kept together along it
// (edge_joint.hpp) after every tick's steps.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "argil/core/haptic/haptic_tick.hpp"

namespace argil {

namespace {

/// A joint moves nothing for a residual below this fraction of eps: a body
/// at rest is not woken by rounding.
constexpr double kJointSlack = 1e-1;

/// The pole pairs of a closed face's two boundary rows across the seam that
/// `pcurve` (one side of it) runs along: u = const rows when it lies on a u
/// boundary, else v = const rows; empty unless the rows coincide (points and
/// weights within 1e-9 of the net's size).
std::vector<std::pair<Eigen::Index, Eigen::Index>> coinciding_rows(const BSplineSurface& s,
                                                                   const BSplineCurve& pcurve) {
  const int nu = s.count(Direction::u), nv = s.count(Direction::v);
  const Eigen::VectorXd mid = evaluate(pcurve, 0.5 * (pcurve.domain_start() + pcurve.domain_end()));
  const double u0 = s.domain_start(Direction::u), u1 = s.domain_end(Direction::u);
  const bool along_u_boundary =
      std::min(std::abs(mid[0] - u0), std::abs(mid[0] - u1)) <= 1e-9 * std::max(u1 - u0, 1e-300);
  std::vector<std::pair<Eigen::Index, Eigen::Index>> pairs;
  if (along_u_boundary) {
    for (int j = 0; j < nv; ++j) pairs.emplace_back(s.pole_index(0, j), s.pole_index(nu - 1, j));
  } else {
    for (int i = 0; i < nu; ++i) pairs.emplace_back(s.pole_index(i, 0), s.pole_index(i, nv - 1));
  }
  const double close = 1e-9 * std::max(control_point_box(s).diagonal(), 1e-300);
  const auto same = [&](const std::pair<Eigen::Index, Eigen::Index>& pq) {
    const auto [p, q] = pq;
    if ((s.control_points.row(p) - s.control_points.row(q)).norm() > close) return false;
    return !s.is_rational() || std::abs(s.weights[p] - s.weights[q]) <= 1e-12 * s.weights[p];
  };
  if (!std::all_of(pairs.begin(), pairs.end(), same)) pairs.clear();
  return pairs;
}

}  // namespace

Result<int> HapticWorld::join(int a, const BSplineCurve& pcurve_a, int b,
                              const BSplineCurve& pcurve_b) {
  for (const int body : {a, b}) {
    if (body < 0 || body >= body_count()) {
      return Status::error(StatusCode::invalid_argument,
                           "join: body " + std::to_string(body) + " is not one of the world's " +
                               std::to_string(body_count()) + " bodies");
    }
  }
  if (is_rigid(a) && is_rigid(b)) {
    return Status::error(
        StatusCode::invalid_argument,
        "join: bodies " + std::to_string(a) + " and " + std::to_string(b) + " are both rigid");
  }
  for (const BSplineCurve* c : {&pcurve_a, &pcurve_b}) {
    const Status s = validate(*c);
    if (!s.ok()) return Status::error(s.code, "join: edge curve: " + s.message);
    if (c->points.cols() != 2) {
      return Status::error(
          StatusCode::invalid_argument,
          "join: edge curve has " + std::to_string(c->points.cols()) + " coordinates, not (u, v)");
    }
  }
  const auto face_of = [&](int body) {
    JointFace f;
    f.surface = &surface(body);
    const Eigen::Index n = f.surface->control_points.rows();
    if (const DeformableBody* d = deformable(body)) {
      f.held = d->fixed();
    } else {
      f.held.assign(static_cast<std::size_t>(n), 1);
    }
    return f;
  };
  const JointFace fa = face_of(a), fb = face_of(b);
  const std::vector<EdgeSample> samples =
      sample_shared_edge(*fa.surface, pcurve_a, *fb.surface, pcurve_b);
  Result<EdgeJoint> joint = EdgeJoint::create(fa, fb, samples, a == b);
  if (!joint.ok()) return joint.status();
  std::vector<std::pair<Eigen::Index, Eigen::Index>> welded;
  if (a == b && deformable(a)) welded = coinciding_rows(*fa.surface, pcurve_a);
  EdgeAhead edge;
  edge.poles = {joint.value().loaded_poles(0), joint.value().loaded_poles(1)};
  for (const EdgeSample& sample : samples)
    edge.points.push_back(evaluate(*fa.surface, sample.uv_a.x(), sample.uv_a.y()));
  for (std::size_t k = 1; k < edge.points.size(); ++k)
    edge.half_spacing =
        std::max(edge.half_spacing, 0.5 * (edge.points[k] - edge.points[k - 1]).norm());
  joints_.push_back({a, b, std::move(joint).value(), std::move(welded)});
  edges_ahead_.push_back(std::move(edge));
  bodies_[static_cast<std::size_t>(a)].joints.push_back(joint_count() - 1);
  if (b != a) bodies_[static_cast<std::size_t>(b)].joints.push_back(joint_count() - 1);
  return joint_count() - 1;
}

Status HapticWorld::prepare_joint(Joint& j, double dt) {
  std::array<StepResponse, 2> response;
  for (int side = 0; side < (j.joint.seam() ? 1 : 2); ++side) {
    const DeformableBody* d = deformable(side == 0 ? j.a : j.b);
    if (!d) continue;
    Result<StepResponse> r =
        d->step_response(j.joint.loaded_poles(side), j.joint.unit_forces(side), dt);
    if (!r.ok()) return r.status();
    response[static_cast<std::size_t>(side)] = std::move(r).value();
  }
  j.joint.set_response(response[0], response[1], dt);
  return Status::success();
}

void HapticWorld::prepare_joint_ahead(const std::vector<char>& near, const Eigen::Vector3d& p_WT,
                                      double dt) {
  // Prepared when first needed, a joint costs that tick 7 to 30 ms on a real
  // part's long edge (two window factorisations and G's eigenpairs), and that
  // tick is one with contact. Its response does not depend on the nets'
  // state, so preparing it while the tool approaches changes nothing else.
  // Not in a tick that had to prepare one: two in one tick doubled the
  // largest tick where the tool engages in contact.
  // Only edges a dent under the tool would reach: within one tool reach of
  // the tool's, and the face's influence length beyond (clay carries a dent
  // 5 mm on: face_recognition face 13's edges, 4.7 and 5.0 mm from a 1.8 mm
  // ball, were prepared in contact). A face it passes costs nothing. (Joints
  // a neighbour's joint carries open later; preparing those when they begin
  // to open prepared, on the screw groove example, a 31 ms seam that never
  // opened by its slack.)
  const double tool_ahead = 2.0 * tool_reach_ + 4.0 * options_.tolerance;
  int first = -1;
  double nearest = std::numeric_limits<double>::infinity();
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    const Body& body = bodies_[b];
    if (!near[b] || !body.deformable) continue;
    const double spread = body.deformable->influence_length();
    const double ahead = tool_ahead + (std::isfinite(spread) ? spread : 0.0);
    for (const int k : body.joints) {
      const Joint& j = joints_[static_cast<std::size_t>(k)];
      EdgeAhead& edge = edges_ahead_[static_cast<std::size_t>(k)];
      if ((j.joint.ready() && j.joint.response_dt() == dt) || edge.failed) continue;
      // Measured again once the tool could have come within `ahead` of it.
      if (edge.distance >= 0.0 && edge.distance - (p_WT - edge.from).norm() > ahead) continue;
      double distance = std::numeric_limits<double>::infinity();
      for (const Eigen::Vector3d& p : edge.points) distance = std::min(distance, (p - p_WT).norm());
      edge.distance = std::max(0.0, distance - edge.half_spacing);
      edge.from = p_WT;
      if (!(edge.distance <= std::min(nearest, ahead))) continue;
      if (!body.deformable->step_may_move_any(edge.poles[j.a == static_cast<int>(b) ? 0 : 1]))
        continue;
      nearest = edge.distance;
      first = k;
    }
  }
  if (first < 0) return;
  const auto k = static_cast<std::size_t>(first);
  edges_ahead_[k].failed = !prepare_joint(joints_[k], dt).ok();
}

Result<int> HapticWorld::enforce_joints(double dt) {
  const double slack = kJointSlack * options_.tolerance;
  int prepared = 0;
  for (Joint& j : joints_) {
    Body& a = bodies_[static_cast<std::size_t>(j.a)];
    Body& b = bodies_[static_cast<std::size_t>(j.b)];
    const bool moving = (a.deformable && !a.asleep) || (b.deformable && !b.asleep);
    if (!moving) continue;
    EdgeJoint::Correction c =
        j.joint.correction(surface(j.a).control_points, surface(j.b).control_points, slack);
    if (!(c.residual > slack)) continue;
    // Built when first needed: most joints of a large model are never reached.
    if (!j.joint.ready() || j.joint.response_dt() != dt) {
      if (Status s = prepare_joint(j, dt); !s.ok()) return s;
      ++prepared;
      c = j.joint.correction(surface(j.a).control_points, surface(j.b).control_points, slack);
    }
    for (const auto& [body, change] : {std::pair{&a, &c.a}, std::pair{&b, &c.b}}) {
      if (!body->deformable) continue;
      DeformableBody& d = *body->deformable;
      if (!change->loaded.empty() && body->joint_force.rows() == 0)
        body->joint_force = ControlNet::Zero(d.masses().size(), 3);
      for (std::size_t k = 0; k < change->loaded.size(); ++k)
        body->joint_force.row(change->loaded[k]) +=
            change->forces.row(static_cast<Eigen::Index>(k));
      if (change->poles.empty()) continue;
      d.displace(change->poles, change->points, change->velocities);
      body->asleep = false;
      const ControlNet& p = d.control_points();
      for (const Eigen::Index pole : change->poles) {
        body->bound.min = body->bound.min.cwiseMin(p.row(pole).transpose());
        body->bound.max = body->bound.max.cwiseMax(p.row(pole).transpose());
      }
    }
  }
  // After every joint: a later one may move a seam's end poles (a cylinder's
  // cap edge meets its seam there), and a tick must end with seams closed.
  for (const Joint& j : joints_)
    if (!bodies_[static_cast<std::size_t>(j.a)].asleep) weld_seam(j);
  return prepared;
}

void HapticWorld::weld_seam(const Joint& j) {
  if (j.welded.empty()) return;
  Body& body = bodies_[static_cast<std::size_t>(j.a)];
  DeformableBody& d = *body.deformable;
  if (!d.weld(j.welded)) return;
  body.asleep = false;
  const ControlNet& p = d.control_points();
  for (const auto& [first, second] : j.welded) {
    body.bound.min = body.bound.min.cwiseMin(p.row(first).transpose());
    body.bound.max = body.bound.max.cwiseMax(p.row(first).transpose());
  }
}

}  // namespace argil
