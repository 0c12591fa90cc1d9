#include "support/sphere_press.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "argil/core/geometry/evaluate.hpp"

namespace argil::test {

namespace {

Eigen::Vector2d at_fraction(const BSplineSurface& s, double a, double b) {
  return {s.domain_start(Direction::u) +
              a * (s.domain_end(Direction::u) - s.domain_start(Direction::u)),
          s.domain_start(Direction::v) +
              b * (s.domain_end(Direction::v) - s.domain_start(Direction::v))};
}

double total_energy(const DeformableBody& body) {
  return body.kinetic_energy() + body.potential_energy();
}

}  // namespace

double normal_turn_bound(double displacement, double radius) {
  const double d = std::min(displacement, radius);
  const double footprint = std::sqrt(std::max(2.0 * radius * d - d * d, 0.0));
  if (footprint <= 0.0) return 0.0;
  if (d >= radius) return 0.5 * M_PI;  // sunk to its equator: the imprint's wall is vertical
  // The smooth bell, or the sphere's own imprint (a plastic dent that took
  // its shape), whose wall at the footprint's rim slopes a / (r - d).
  return std::max(std::atan(2.0 * d / footprint), std::atan(footprint / (radius - d)));
}

double largest_normal_turn(const BSplineSurface& before, const BSplineSurface& after, int samples,
                           double* largest_move) {
  struct Sample {
    Eigen::Vector3d n0, n1;
    double speed0 = 0.0, speed1 = 0.0;
    double move = 0.0;
  };
  std::vector<Sample> grid;
  grid.reserve(static_cast<std::size_t>(samples * samples));
  std::vector<double> speeds;
  for (int a = 0; a < samples; ++a) {
    for (int b = 0; b < samples; ++b) {
      const Eigen::Vector2d uv =
          at_fraction(before, a / double(samples - 1), b / double(samples - 1));
      const SurfaceDerivatives d0 = evaluate_derivatives(before, uv.x(), uv.y(), 1);
      const SurfaceDerivatives d1 = evaluate_derivatives(after, uv.x(), uv.y(), 1);
      Sample s;
      s.n0 = d0.du.cross(d0.dv);
      s.n1 = d1.du.cross(d1.dv);
      s.speed0 = s.n0.norm();
      s.speed1 = s.n1.norm();
      s.move = (d1.point - d0.point).norm();
      speeds.push_back(s.speed0);
      grid.push_back(s);
    }
  }
  std::nth_element(speeds.begin(), speeds.begin() + static_cast<long>(speeds.size() / 2),
                   speeds.end());
  // Where |S_u x S_v| is below a thousandth of its median (near a collapsed
  // edge or a degenerate corner) the parametric normal is ill-conditioned: a
  // displacement gradient a thousandth of the surface's own turns it by order
  // one without the shape changing, so those samples say nothing.
  const double floor = 1e-3 * speeds[speeds.size() / 2];
  double turn = 0.0, move = 0.0;
  for (const Sample& s : grid) {
    move = std::max(move, s.move);
    if (!(s.speed0 > floor && s.speed1 > floor)) continue;
    // atan2 of |a x b| and a . b is accurate at small and large angles alike.
    const double angle = std::atan2(s.n0.cross(s.n1).norm(), s.n0.dot(s.n1));
    turn = std::max(turn, angle);
  }
  if (largest_move != nullptr) *largest_move = move;
  return turn;
}

PressOutcome press_sphere(const BSplineSurface& face, const SpherePress& press) {
  PressOutcome out;
  Result<HapticWorld> created = HapticWorld::create(SphereToolShape{press.radius}, press.options);
  if (!created.ok()) {
    out.error = "world: " + created.status().message;
    return out;
  }
  HapticWorld world = std::move(created).value();
  const Result<int> added =
      world.add_deformable(face, press.material, press.conditions, press.friction);
  if (!added.ok()) {
    out.error = "face: " + added.status().message;
    return out;
  }
  const DeformableBody& body = *world.deformable(added.value());
  out.rest = body.control_points();

  const SurfaceDerivatives at = evaluate_derivatives(face, press.uv.x(), press.uv.y(), 1);
  const Eigen::Vector3d normal = unit_normal(at);
  const Eigen::Vector3d touching = at.point + press.radius * normal;
  out.device_penetration = press.depth;
  {
    const Eigen::Vector3d lowest = touching - press.depth * normal;
    const int n = 4 * press.samples;
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b) {
        const Eigen::Vector2d uv = at_fraction(face, a / double(n - 1), b / double(n - 1));
        out.device_penetration =
            std::max(out.device_penetration,
                     press.radius - (lowest - evaluate(face, uv.x(), uv.y())).norm());
      }
  }
  const int approach_ticks =
      std::max(1, static_cast<int>(std::lround(press.approach_time / press.dt)));
  const int press_ticks = static_cast<int>(std::lround(press.press_time / press.dt));
  const int release_ticks = static_cast<int>(std::lround(press.release_time / press.dt));

  const auto track = [&] {
    const ControlNet& p = body.control_points();
    if (!p.allFinite()) {
      out.finite = false;
      return false;
    }
    out.max_control_move =
        std::max(out.max_control_move, (p - out.rest).rowwise().norm().maxCoeff());
    return true;
  };
  bool checked = false;
  const auto check_normals = [&] {
    double move = 0.0;
    const double turn = largest_normal_turn(face, body.surface(), press.samples, &move);
    const double bound = normal_turn_bound(move, press.radius);
    // Keep the check that comes closest to (or goes furthest past) its bound.
    if (!checked || turn - bound > out.normal_turn - out.turn_bound) {
      out.normal_turn = turn;
      out.displacement = move;
      out.turn_bound = bound;
    }
    checked = true;
  };

  for (int t = 0; t < press_ticks; ++t) {
    const double along = std::min(1.0, static_cast<double>(t) / approach_ticks);
    const double height = press.approach - along * (press.approach + press.depth);
    const DeviceSample device{.tick = t,
                              .t = t * press.dt,
                              .X_WD = Pose::at(touching + height * normal),
                              .engaged = true};
    const TickResult r = world.step(device, press.dt);
    if (!r.status.ok()) {
      out.error = "tick " + std::to_string(t) + ": " + r.status.message;
      return out;
    }
    out.peak_force = std::max(out.peak_force, r.body_force.norm());
    if (r.contacts > 0) ++out.contact_ticks;
    if (!track()) return out;
    if ((t + 1) % press.check_every == 0 || t + 1 == press_ticks) check_normals();
  }
  out.pressed = body.control_points();
  out.dent = -(evaluate(body.surface(), press.uv.x(), press.uv.y()) - at.point).dot(normal);

  out.energy_at_release = total_energy(body);
  double previous = out.energy_at_release;
  for (int t = 0; t < release_ticks; ++t) {
    const DeviceSample device{.tick = press_ticks + t,
                              .t = (press_ticks + t) * press.dt,
                              .X_WD = Pose::at(touching + 10.0 * press.radius * normal),
                              .engaged = false};
    const TickResult r = world.step(device, press.dt);
    if (!r.status.ok()) {
      out.error = "release tick " + std::to_string(t) + ": " + r.status.message;
      return out;
    }
    if (!track()) return out;
    const double e = total_energy(body);
    if (out.energy_at_release > 0.0)
      out.energy_rise = std::max(out.energy_rise, (e - previous) / out.energy_at_release);
    previous = e;
  }
  out.energy_final = previous;
  out.final = body.control_points();
  return out;
}

}  // namespace argil::test
