// Sleep and reach (docs/deformation.md): bodies out of the tool's reach are
// left out of its queries, and a settled deformable body out of reach is not
// stepped; neither changes a single bit of what the tool feels.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "argil/core.hpp"
#include "support/test_plates.hpp"

namespace {

constexpr double kEps = 0.01;
constexpr double kRadius = 2.0;
constexpr double kDt = 1e-3;

/// A flat 10 x 10 mm bicubic panel with 8 x 8 poles, its corner at `corner`.
argil::BSplineSurface panel_at(const Eigen::Vector3d& corner) {
  argil::BSplineSurface s = argil::test::flat_bicubic_panel(10.0, 5);
  s.control_points.rowwise() += corner.transpose();
  return s;
}

/// sleep and cull false: the reference where every body is queried and stepped.
argil::HapticWorld sphere_world(bool sleep, bool cull) {
  argil::WorldOptions o;
  o.tolerance = kEps;
  o.coupling = {.stiffness = 1.0, .damping = 0.0, .max_force = 100.0};
  o.sleep = sleep;
  o.cull = cull;
  auto w = argil::HapticWorld::create(argil::SphereToolShape{kRadius}, o);
  REQUIRE(w.ok());
  return std::move(w).value();
}

void add_panel(argil::HapticWorld& w, const Eigen::Vector3d& corner) {
  argil::BoundaryConditions held;
  held.fixed_u0 = held.fixed_u1 = true;
  REQUIRE(w.add_deformable(panel_at(corner), argil::Material{}, held, 0.3).ok());
}

argil::DeviceSample at(const Eigen::Vector3d& p, bool engaged = true) {
  return {.tick = 0, .t = 0.0, .X_WD = argil::Pose::at(p), .engaged = engaged};
}

/// The largest |P - P_rest| of a deformable body [mm].
double stretch(const argil::DeformableBody& body) {
  return (body.control_points() - body.rest_control_points()).rowwise().norm().maxCoeff();
}

/// Every bit a tick returns, and every body's control points afterwards.
void require_identical(const argil::TickResult& a, const argil::TickResult& b,
                       const argil::HapticWorld& wa, const argil::HapticWorld& wb) {
  REQUIRE(a.status.ok());
  REQUIRE(b.status.ok());
  REQUIRE(a.force == b.force);
  REQUIRE(a.body_force == b.body_force);
  REQUIRE(a.contacts == b.contacts);
  REQUIRE(a.regions == b.regions);
  REQUIRE(a.max_depth == b.max_depth);
  REQUIRE(a.proxy.X_WT.p == b.proxy.X_WT.p);
  REQUIRE(a.proxy.stuck == b.proxy.stuck);
  REQUIRE(a.body_contacts.size() == b.body_contacts.size());
  for (std::size_t k = 0; k < a.body_contacts.size(); ++k) {
    REQUIRE(a.body_contacts[k].size() == b.body_contacts[k].size());
    for (std::size_t c = 0; c < a.body_contacts[k].size(); ++c) {
      REQUIRE(a.body_contacts[k][c].point == b.body_contacts[k][c].point);
      REQUIRE(a.body_contacts[k][c].normal == b.body_contacts[k][c].normal);
      REQUIRE(a.body_contacts[k][c].depth == b.body_contacts[k][c].depth);
    }
  }
  for (int k = 0; k < wa.body_count(); ++k) {
    CAPTURE(k, wa.asleep(k));
    REQUIRE(wa.surface(k).control_points == wb.surface(k).control_points);
  }
}

}  // namespace

TEST_CASE("sleep: far bodies keep their control points and sleep while a plate is pressed",
          "[haptic][sleep]") {
  argil::HapticWorld w = sphere_world(true, true);
  add_panel(w, {0, 0, 0});  // pressed
  const std::vector<Eigen::Vector3d> far = {{60, 0, 0}, {0, 60, 0}, {-60, 0, 10}, {0, 0, 50}};
  for (const Eigen::Vector3d& corner : far) add_panel(w, corner);
  REQUIRE(w.add_rigid(panel_at({60, 60, 0}), 0.3).ok());
  std::vector<argil::ControlNet> before;
  for (int b = 0; b < w.body_count(); ++b) before.push_back(w.surface(b).control_points);

  for (int t = 0; t < 400; ++t) {
    const double z = std::max(kRadius - 0.5, kRadius + 1.0 - 0.02 * t);  // down, then hold
    REQUIRE(w.step(at({5, 5, z}), kDt).status.ok());
    for (int b = 1; b < w.body_count(); ++b) {
      CAPTURE(t, b);
      REQUIRE(w.surface(b).control_points == before[static_cast<std::size_t>(b)]);
      if (!w.is_rigid(b)) REQUIRE(w.asleep(b));
    }
  }
  CHECK(w.proxy().in_contact);
  CHECK_FALSE(w.asleep(0));
  CHECK_FALSE(w.asleep(w.body_count() - 1));  // rigid: never asleep
  CHECK((w.surface(0).control_points - before[0]).cwiseAbs().maxCoeff() > 0.01);
}

TEST_CASE("sleep: a tool moving fast onto a sleeping body feels it exactly as a never-sleeping one",
          "[haptic][sleep]") {
  // 3 mm per tick (3 m/s) from 40 mm above, then across the plate: the body
  // sleeps until the tool is near, and every tick, the first contact
  // included, matches the world where nothing sleeps to the last bit (a
  // body at rest is exactly at rest: its step changes no bit).
  for (const double speed : {0.5, 3.0, 8.0}) {  // [mm per tick]
    CAPTURE(speed);
    argil::HapticWorld sleeping = sphere_world(true, true);
    argil::HapticWorld reference = sphere_world(false, false);
    for (argil::HapticWorld* w : {&sleeping, &reference}) add_panel(*w, {0, 0, 0});
    bool slept = false, touched = false;
    Eigen::Vector3d device(3.0, 4.0, 40.0);
    for (int t = 0; t < 200; ++t) {
      CAPTURE(t);
      if (device.z() > kRadius - 0.7)
        device.z() = std::max(kRadius - 0.7, device.z() - speed);
      else
        device.x() = std::min(8.0, device.x() + 0.05);
      const argil::TickResult a = sleeping.step(at(device), kDt);
      const argil::TickResult b = reference.step(at(device), kDt);
      require_identical(a, b, sleeping, reference);
      if (a.contacts == 0 && !touched) slept = slept || sleeping.asleep(0);
      if (a.contacts > 0) touched = true;
      if (touched) REQUIRE_FALSE(sleeping.asleep(0));
    }
    CHECK(slept);
    CHECK(touched);
  }
}

/// The stroke of the reach tests: a row of deformable and rigid panels at
/// several heights; the sphere sweeps along it just above them, pressing some,
/// passing others, rising off the first one early.
void add_row(argil::HapticWorld& w) {
  add_panel(w, {0, 0, 0});
  REQUIRE(w.add_rigid(panel_at({12, 0, -1.0}), 0.3).ok());
  add_panel(w, {24, 0, 0.5});
  REQUIRE(w.add_rigid(panel_at({36, 0, -8.0}), 0.0).ok());
  add_panel(w, {48, 0, -0.3});
  add_panel(w, {0, 30, 0});  // beside the stroke, never reached
}

Eigen::Vector3d stroke(int t) {
  return {1.0 + 0.04 * t, 5.0, kRadius - 0.6 + 0.8 * std::sin(0.01 * t)};
}

TEST_CASE("reach: a stroke past several bodies gives the unculled world's contacts to the bit",
          "[haptic][sleep]") {
  argil::HapticWorld culled = sphere_world(false, true);
  argil::HapticWorld reference = sphere_world(false, false);
  add_row(culled);
  add_row(reference);
  int touching = 0;
  for (int t = 0; t < 1500; ++t) {
    CAPTURE(t);
    const argil::TickResult a = culled.step(at(stroke(t)), kDt);
    const argil::TickResult b = reference.step(at(stroke(t)), kDt);
    require_identical(a, b, culled, reference);
    touching += a.contacts > 0 ? 1 : 0;
  }
  CHECK(touching > 300);
}

TEST_CASE("sleep: over the stroke, a body that slept differs by less than its rest threshold",
          "[haptic][sleep]") {
  // Not bit-identical: a pressed body that settled sleeps where the
  // never-sleeping one keeps creeping towards its rest shape. Both are within
  // kSleepFraction eps of it then, so the control points differ by less than
  // twice that, and the force by less than the coupling stiffness (1 N/mm)
  // times it.
  argil::HapticWorld sleeping = sphere_world(true, true);
  argil::HapticWorld reference = sphere_world(false, false);
  add_row(sleeping);
  add_row(reference);
  const double bound = 2.0 * argil::kSleepFraction * kEps;
  double worst_points = 0.0, worst_force = 0.0;
  int slept = 0;
  for (int t = 0; t < 1500; ++t) {
    CAPTURE(t);
    const argil::TickResult a = sleeping.step(at(stroke(t)), kDt);
    const argil::TickResult b = reference.step(at(stroke(t)), kDt);
    REQUIRE(a.status.ok());
    REQUIRE(a.contacts == b.contacts);
    worst_force = std::max(worst_force, (a.force - b.force).norm());
    for (int k = 0; k < sleeping.body_count(); ++k) {
      worst_points = std::max(
          worst_points, (sleeping.surface(k).control_points - reference.surface(k).control_points)
                            .cwiseAbs()
                            .maxCoeff());
      slept += sleeping.asleep(k) ? 1 : 0;
    }
  }
  CHECK(slept > 0);
  CHECK(worst_points < bound);
  CHECK(worst_force < 1.0 * bound);
}

TEST_CASE("sleep: a released body steps until it settles, sleeps, and wakes for the tool",
          "[haptic][sleep]") {
  for (const bool engaged_release : {true, false}) {
    CAPTURE(engaged_release);
    argil::HapticWorld w = sphere_world(true, true);
    add_panel(w, {0, 0, 0});
    const argil::DeformableBody& plate = *w.deformable(0);
    for (int t = 0; t < 300; ++t) {
      const double z = std::max(kRadius - 1.0, kRadius + 1.0 - 0.02 * t);
      REQUIRE(w.step(at({5, 5, z}), kDt).status.ok());
    }
    REQUIRE(stretch(plate) > 100.0 * argil::kSleepFraction * kEps);
    // Lift the tool far away (or let go): the plate springs back.
    const double rest = argil::kSleepFraction * kEps;
    int awake_ticks = 0;
    argil::ControlNet frozen;
    for (int t = 0; t < 2000; ++t) {
      CAPTURE(t);
      REQUIRE(w.step(at({5, 5, 60}, engaged_release), kDt).status.ok());
      if (!w.asleep(0)) {
        ++awake_ticks;
        REQUIRE(frozen.size() == 0);  // once asleep it stays asleep
        continue;
      }
      // Asleep only once settled: within rest of its rest shape, velocities zero.
      REQUIRE(stretch(plate) < rest);
      REQUIRE(plate.velocities().cwiseAbs().maxCoeff() == 0.0);
      if (frozen.size() == 0) frozen = plate.control_points();
      REQUIRE(plate.control_points() == frozen);
    }
    REQUIRE(frozen.size() > 0);
    CHECK(awake_ticks > 5);  // it kept stepping after the tool left
    // The tool returns: the plate is awake before the first contact.
    bool touched = false;
    for (int t = 0; t < 100; ++t) {
      CAPTURE(t);
      const double z = std::max(kRadius - 0.5, 60.0 - 2.0 * t);
      const argil::TickResult r = w.step(at({5, 5, z}), kDt);
      REQUIRE(r.status.ok());
      if (r.contacts > 0) {
        touched = true;
        REQUIRE_FALSE(w.asleep(0));
      }
    }
    CHECK(touched);
    CHECK(plate.control_points() != frozen);
  }
}
