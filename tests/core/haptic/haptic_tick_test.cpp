// The haptic tick (docs/deformation.md): Coulomb stick and slip, no tunnelling at 1 m/s
// and beyond, force clamp, elastic return and plastic dents under a tool,
// determinism, and the B-spline tool.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "argil/core.hpp"
#include "support/tool_shapes.hpp"

namespace {

using argil::ControlNet;

using argil::test::bowl_cap;
using argil::test::wavy_sheet;

/// Height of a surface over (x, y), found by bisection on its parameters
/// (the sheets here are graphs over a square with x = f(u), y = g(v) monotone).
double height(const argil::BSplineSurface& s, double x, double y) {
  double u0 = 0, u1 = 1, v0 = 0, v1 = 1;
  for (int i = 0; i < 60; ++i) {
    const double um = 0.5 * (u0 + u1), vm = 0.5 * (v0 + v1);
    const Eigen::Vector3d p = argil::evaluate(s, um, vm);
    (p.x() < x ? u0 : u1) = um;
    (p.y() < y ? v0 : v1) = vm;
  }
  return argil::evaluate(s, 0.5 * (u0 + u1), 0.5 * (v0 + v1)).z();
}

argil::HapticWorld world(const argil::ToolShape& tool, double eps = 0.01,
                         double max_force = 100.0) {
  argil::WorldOptions o;
  o.tolerance = eps;
  o.coupling = {.stiffness = 1.0, .damping = 0.0, .max_force = max_force};
  auto w = argil::HapticWorld::create(tool, o);
  REQUIRE(w.ok());
  return std::move(w).value();
}

argil::DeviceSample at(double x, double y, double z) {
  return {.tick = 0, .t = 0.0, .X_WD = argil::Pose::at({x, y, z}), .engaged = true};
}

/// Adds `s` as a panel of 1 mm of a dense soft layer yielding at `yield`
/// [mm], with `damping` [s], held along its u edges (friction 0.3).
void add_soft_panel(argil::HapticWorld& w, const argil::BSplineSurface& s, double yield,
                    double damping = 0.01) {
  argil::Material m;
  m.density = 1e4;
  m.thickness = 1.0;
  m.youngs_modulus = 0.1;
  m.foundation_stiffness = 0.02;
  m.damping = damping;
  m.yield = yield;
  argil::BoundaryConditions bc;
  bc.fixed_u0 = bc.fixed_u1 = true;
  REQUIRE(w.add_deformable(s, m, bc, 0.3).ok());
}

/// The bowl cap landed on a soft panel (yield 0.05 mm) at (45, 45) with the
/// hand 3 mm under the panel, at tolerance `eps` (the force clamped at 20 N).
argil::HapticWorld cap_on_soft_panel(double eps) {
  argil::HapticWorld w = world(argil::SurfaceToolShape{bowl_cap()}, eps, 20.0);
  add_soft_panel(w, wavy_sheet(10, 10.0, 0.0), 0.05);
  REQUIRE(w.step(at(45, 45, 10), 1e-3).status.ok());
  // The cap's lowest point is 1.2 mm above its frame's origin.
  for (int t = 0; t < 5 && !w.proxy().in_contact; ++t)
    REQUIRE(w.step(at(45, 45, -3.0), 1e-3).status.ok());
  REQUIRE(w.proxy().in_contact);
  return w;
}

/// A flat wall in the plane x = `x`, across y in [30, 60] and z in [-5, 10].
argil::BSplineSurface wall_at(double x) {
  argil::BSplineSurface wall = wavy_sheet(4, 10.0, 0.0);
  for (Eigen::Index k = 0; k < wall.control_points.rows(); ++k) {
    const Eigen::RowVector3d p = wall.control_points.row(k);
    wall.control_points.row(k) << x, 30.0 + p.x(), -5.0 + p.y() / 2.0;
  }
  return wall;
}

/// Brings the tool down at (x, y) from 10 mm up with the hand `press` under
/// where it lands, and holds it there three ticks; returns the height it
/// rests at.
double land(argil::HapticWorld& w, double x, double y, double press) {
  REQUIRE(w.step(at(x, y, 10), 1e-3).status.ok());
  REQUIRE(w.step(at(x, y, -press), 1e-3).status.ok());  // lands
  const double rest = w.proxy().X_WT.p.z();
  for (int t = 0; t < 3; ++t) REQUIRE(w.step(at(x, y, rest - press), 1e-3).status.ok());
  return rest;
}

/// A copy of body b's hierarchy to query (queries refine its lazy bounds;
/// the world hands out const access only).
argil::SurfaceHierarchy queryable(const argil::HapticWorld& w, int b) { return w.hierarchy(b); }

}  // namespace

TEST_CASE("friction: a pull below mu N sticks, above it slips to mu N", "[haptic]") {
  const double mu = 0.5, radius = 5.0, press = 2.0;  // N = k press = 2 N, mu N = 1 N
  for (const double pull : {0.5, 0.9, 1.5, 3.0}) {   // tangential offset [mm] = pull [N] at k = 1
    CAPTURE(pull);
    argil::HapticWorld w = world(argil::SphereToolShape{radius});
    REQUIRE(w.add_rigid(wavy_sheet(10, 10.0, 0.0), mu).ok());
    REQUIRE(w.step(at(45, 45, 20), 1e-3).status.ok());
    for (int t = 0; t < 3; ++t) REQUIRE(w.step(at(45, 45, radius - press), 1e-3).status.ok());
    REQUIRE(w.proxy().in_contact);
    const argil::TickResult r = w.step(at(45 + pull, 45, radius - press), 1e-3);
    CHECK(r.force.z() == Approx(press).epsilon(1e-3));  // N, to the projection tolerance
    if (pull < mu * press) {
      CHECK(r.proxy.stuck);
      CHECK(r.proxy.X_WT.p.x() == 45.0);
      CHECK(r.force.x() == Approx(-pull).epsilon(1e-9));
    } else {
      CHECK_FALSE(r.proxy.stuck);
      CHECK(r.proxy.X_WT.p.x() == Approx(45 + pull - mu * press).epsilon(1e-6));
      CHECK(-r.force.x() == Approx(mu * press).epsilon(1e-4));  // |F_t| = mu N
    }
  }
}

TEST_CASE("without friction the proxy slides to the device's foot on the surface", "[haptic]") {
  argil::HapticWorld w = world(argil::SphereToolShape{4.0});
  REQUIRE(w.add_rigid(wavy_sheet(10, 10.0, 0.0), 0.0).ok());
  REQUIRE(w.step(at(30, 30, 10), 1e-3).status.ok());
  REQUIRE(w.step(at(30, 30, 1), 1e-3).status.ok());
  const argil::TickResult r = w.step(at(37, 31, 1), 1e-3);
  CHECK((r.proxy.X_WT.p - Eigen::Vector3d(37, 31, 4)).norm() < 0.01);  // within eps
  CHECK(r.force.head<2>().norm() < 0.01);
}

TEST_CASE("a sphere sweeping at 1 m/s and 10 m/s never sinks deeper than eps", "[haptic]") {
  const argil::BSplineSurface s = wavy_sheet(20, 10.0, 3.0);
  const double eps = 0.01, radius = 3.0;
  for (const double speed : {1.0, 10.0}) {  // [m/s] = [mm per 1 ms tick]
    CAPTURE(speed);
    argil::HapticWorld w = world(argil::SphereToolShape{radius}, eps);
    REQUIRE(w.add_rigid(s, 0.3).ok());
    REQUIRE(w.step(at(20, 95, height(s, 20, 95) + 10), 1e-3).status.ok());
    for (double x = 20; x <= 170; x += speed) {
      // The device runs 2 mm under the surface: the proxy must ride on top.
      const argil::TickResult r = w.step(at(x, 95, height(s, x, 95) - 2.0), 1e-3);
      CHECK(r.max_depth <= eps);
      argil::SurfaceHierarchy h = queryable(w, 0);
      const argil::ClosestPoint cp = argil::closest_point(h, r.proxy.X_WT.p);
      CHECK(cp.distance >= radius - eps);
      CHECK(cp.signed_distance > 0.0);  // still on the +z side
    }
  }
}

TEST_CASE("a device plunging through a sheet in one tick leaves the proxy on top", "[haptic]") {
  const argil::BSplineSurface s = wavy_sheet(10, 10.0, 1.0);
  for (const double radius : {2.0, 0.0}) {  // sphere and point tool
    CAPTURE(radius);
    argil::HapticWorld w = world(argil::SphereToolShape{radius});
    REQUIRE(w.add_rigid(s, 0.2).ok());
    REQUIRE(w.step(at(41, 47, 15), 1e-3).status.ok());
    const argil::TickResult r = w.step(at(43, 46, -60), 1e-3);
    argil::SurfaceHierarchy h = queryable(w, 0);
    const argil::ClosestPoint cp = argil::closest_point(h, r.proxy.X_WT.p);
    CHECK(cp.signed_distance > 0.0);
    CHECK(cp.distance >= radius - 0.01);
    CHECK(r.proxy.in_contact);
    CHECK(r.force.z() > 0.0);  // pulls the hand up towards the proxy
  }
}

TEST_CASE("the device force is clamped to max_force", "[haptic]") {
  argil::HapticWorld w = world(argil::SphereToolShape{5.0}, 0.01, 8.0);
  REQUIRE(w.add_rigid(wavy_sheet(10, 10.0, 0.0), 0.3).ok());
  REQUIRE(w.step(at(45, 45, 20), 1e-3).status.ok());
  const argil::TickResult r = w.step(at(45, 45, -100), 1e-3);
  CHECK(r.clamped);
  CHECK(r.force.norm() == Approx(8.0).epsilon(1e-12));
  CHECK(r.force.z() > 0.0);
  const argil::TickResult light = w.step(at(45, 45, 3), 1e-3);
  CHECK_FALSE(light.clamped);
  CHECK(light.force.z() == Approx(2.0).epsilon(1e-3));
}

TEST_CASE("a tool dents an elastic panel, which returns to rest after it leaves", "[haptic]") {
  const argil::BSplineSurface s = wavy_sheet(10, 10.0, 0.0);
  for (const double yield : {std::numeric_limits<double>::infinity(), 0.3}) {
    CAPTURE(yield);
    argil::HapticWorld w = world(argil::SphereToolShape{6.0}, 0.01, 20.0);
    add_soft_panel(w, s, yield);
    const ControlNet original = w.deformable(0)->control_points();
    REQUIRE(w.step(at(45, 45, 20), 1e-3).status.ok());
    double deepest = 0.0;
    for (int t = 0; t < 300; ++t) {
      const argil::TickResult r = w.step(at(45, 45, 6.0 - 4.0), 1e-3);  // 4 mm into the rest
      REQUIRE(r.status.ok());
      CHECK(r.max_depth <= 0.01);
      deepest =
          std::max(deepest, (w.deformable(0)->control_points() - original).cwiseAbs().maxCoeff());
    }
    CHECK(deepest > 0.2);  // the panel gave way
    CHECK(w.proxy().in_contact);
    for (int t = 0; t < 3000; ++t) REQUIRE(w.step(at(45, 45, 40), 1e-3).status.ok());
    const double kept = (w.deformable(0)->control_points() - original).cwiseAbs().maxCoeff();
    if (!std::isfinite(yield)) {
      CHECK(kept < 1e-3);  // back to rest within 1 um
    } else {
      CHECK(kept > 0.1);  // the dent beyond yield stays
      CHECK((w.deformable(0)->control_points() - w.deformable(0)->rest_control_points())
                .cwiseAbs()
                .maxCoeff() < 1e-3);  // and it is the new rest state
    }
  }
}

TEST_CASE("the same inputs give bit-identical forces and surfaces", "[haptic]") {
  const auto run = [] {
    argil::HapticWorld w = world(argil::SphereToolShape{4.0}, 0.01, 10.0);
    argil::Material m;
    m.density = 1e4;
    m.thickness = 1.0;
    m.youngs_modulus = 2.0;
    m.foundation_stiffness = 1.0;
    m.yield = 0.5;
    REQUIRE(w.add_deformable(wavy_sheet(8, 10.0, 2.0), m, {}, 0.3).ok());
    REQUIRE(w.add_rigid(wavy_sheet(4, 30.0, 0.0), 0.4).ok());  // a floor under it
    std::vector<Eigen::Vector3d> forces;
    for (int t = 0; t < 400; ++t) {
      const double a = 0.01 * t;
      forces.push_back(
          w.step(at(35 + 10 * std::cos(a), 35 + 10 * std::sin(a), 3.0 - 2 * std::sin(3 * a)), 1e-3)
              .force);
    }
    return std::make_pair(forces, w.surface(0).control_points);
  };
  const auto a = run();
  const auto b = run();
  REQUIRE(a.first.size() == b.first.size());
  for (std::size_t i = 0; i < a.first.size(); ++i) CHECK(a.first[i] == b.first[i]);
  CHECK(a.second == b.second);
}

TEST_CASE("a B-spline tool stops on a surface without crossing it and slides along", "[haptic]") {
  const argil::BSplineSurface tool = bowl_cap();
  const argil::BSplineSurface floor = wavy_sheet(10, 10.0, 1.0);
  const double eps = 0.05;
  argil::HapticWorld w = world(argil::SurfaceToolShape{tool}, eps, 20.0);
  REQUIRE(w.add_rigid(floor, 0.0).ok());
  argil::OperatorCache cache;
  argil::SurfaceHierarchy floor_h = argil::SurfaceHierarchy::build(floor, cache).value();
  argil::SurfaceHierarchy tool_h = argil::SurfaceHierarchy::build(tool, cache).value();
  REQUIRE(w.step(at(30, 40, 10), 1e-3).status.ok());
  for (double x = 30; x <= 60; x += 1.0) {  // 1 m/s, the device 3 mm under the floor
    const argil::TickResult r = w.step(at(x, 40, height(floor, x, 40) - 3.0), 1e-3);
    ControlNet posed = tool.control_points;
    posed.rowwise() += r.proxy.X_WT.p.transpose();
    tool_h.set_control_points(posed);
    const argil::CollisionResult c =
        argil::collide(floor_h, tool_h, {.tolerance = eps, .refine = false});
    CHECK(c.curves.empty());  // never crosses
    CHECK(r.proxy.in_contact);
    CHECK(r.force.z() > 1.0);  // the hand is pulled up towards the proxy
  }
}

TEST_CASE("a B-spline tool turned into a floor keeps the rotation its move stopped at",
          "[haptic]") {
  // The hand turns the resting cap in place by 0.3 rad about x, which dips
  // its rim 3 mm into the floor: the proxy stops turning where the rim
  // touches, and its pose (rotation included) never crosses, with or without
  // friction. Turned back, it follows the hand again.
  const double eps = 0.05, press = 2.0;
  const argil::BSplineSurface tool = bowl_cap();
  argil::OperatorCache cache;
  argil::SurfaceToolProxy check =
      argil::SurfaceToolProxy::create(tool, eps, cache, argil::WorldOptions{}.max_contacts).value();
  for (const double mu : {0.0, 0.5}) {
    CAPTURE(mu);
    argil::HapticWorld w = world(argil::SurfaceToolShape{tool}, eps);
    REQUIRE(w.add_rigid(wavy_sheet(10, 10.0, 0.0), mu).ok());
    const argil::SurfaceHierarchy floor = w.hierarchy(0);
    const std::vector<const argil::SurfaceHierarchy*> floors{&floor};
    REQUIRE(w.step(at(45, 45, 10), 1e-3).status.ok());
    REQUIRE(w.step(at(45, 45, -press), 1e-3).status.ok());
    REQUIRE(w.proxy().in_contact);
    const double rest = w.proxy().X_WT.p.z();
    for (int t = 1; t <= 6; ++t) {
      argil::DeviceSample turned = at(45, 45, rest - press);
      turned.X_WD.R = Eigen::Quaterniond(Eigen::AngleAxisd(0.05 * t, Eigen::Vector3d::UnitX()));
      const argil::TickResult r = w.step(turned, 1e-3);
      REQUIRE(r.status.ok());
      CAPTURE(t);
      CHECK(r.proxy.in_contact);
      CHECK_FALSE(check.crossing(floors, r.proxy.X_WT).crosses);
    }
    const argil::Pose& stopped = w.proxy().X_WT;
    REQUIRE(
        check
            .crossing(floors, {Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX())),
                               stopped.p})
            .crosses);
    const double turn = stopped.R.angularDistance(Eigen::Quaterniond::Identity());
    CHECK(turn > 0.0);  // it turned until the rim touched
    CHECK(turn < 0.3);  // and no further
    const argil::TickResult back = w.step(at(45, 45, rest - press), 1e-3);
    REQUIRE(back.status.ok());
    // Turned back the rim rises from the floor: nothing blocks the move,
    // which ends at the device's rotation (up to the slerp's rounding).
    CHECK(back.proxy.X_WT.R.angularDistance(Eigen::Quaterniond::Identity()) < 1e-12);
    CHECK_FALSE(check.crossing(floors, back.proxy.X_WT).crosses);
  }
}

TEST_CASE("a B-spline tool sticks below mu N and slips to mu N within eps and beyond", "[haptic]") {
  const double mu = 0.5, press = 2.0, eps = 0.05;  // N = k press = 2 N, mu N = 1 N
  // Pulls [N] = tangential offsets [mm] at k = 1: two that stick, a slip of
  // eps / 2 (one swept query) and slips of 0.5 and 2 mm (stick point tested,
  // then a move).
  for (const double pull : {0.5, 0.9, mu * press + 0.5 * eps, 1.5, 3.0}) {
    CAPTURE(pull);
    argil::HapticWorld w = world(argil::SurfaceToolShape{bowl_cap()}, eps);
    REQUIRE(w.add_rigid(wavy_sheet(10, 10.0, 0.0), mu).ok());
    REQUIRE(w.step(at(45, 45, 10), 1e-3).status.ok());
    REQUIRE(w.step(at(45, 45, -press), 1e-3).status.ok());  // lands on the floor
    REQUIRE(w.proxy().in_contact);
    const double landed = w.proxy().X_WT.p.z(), gap = -w.proxy().max_depth;
    // Held pressed on a floor that does not move, it settles straight down to
    // 3/4 eps off it when it landed farther, and stays.
    REQUIRE(w.step(at(45, 45, landed - press), 1e-3).status.ok());
    const double rest = w.proxy().X_WT.p.z();
    CHECK(rest == Approx(landed - std::max(gap - 0.75 * eps, 0.0)).margin(1e-12));
    CHECK(w.proxy().max_depth == Approx(-std::min(gap, 0.75 * eps)).margin(1e-12));
    for (int t = 0; t < 3; ++t) REQUIRE(w.step(at(45, 45, rest - press), 1e-3).status.ok());
    REQUIRE(w.proxy().X_WT.p.z() == rest);
    REQUIRE(w.proxy().outward_normal.z() == Approx(1.0).epsilon(1e-9));
    const argil::TickResult r = w.step(at(45 + pull, 45, rest - press), 1e-3);
    REQUIRE(r.status.ok());
    CHECK(r.proxy.in_contact);
    CHECK(r.proxy.X_WT.p.z() == rest);
    CHECK(r.force.z() == Approx(press).epsilon(1e-12));
    if (pull < mu * press) {
      CHECK(r.proxy.stuck);
      CHECK(r.proxy.X_WT.p.x() == 45.0);
      CHECK(r.force.x() == Approx(-pull).epsilon(1e-12));
    } else {
      CHECK_FALSE(r.proxy.stuck);
      CHECK(r.proxy.X_WT.p.x() == Approx(45 + pull - mu * press).epsilon(1e-12));
      CHECK(-r.force.x() == Approx(mu * press).epsilon(1e-9));  // |F_t| = mu N
    }
  }
}

TEST_CASE("a B-spline tool whose short slip would cross a wall stops before it with friction",
          "[haptic]") {
  // The cap rests on a floor with its rim within eps of a wall (a contact),
  // and is pulled towards the wall past mu N by a slip shorter than eps but
  // longer than the gap. That slip is one swept query, which crosses the
  // wall: the tick then tests the stick point and moves from there towards
  // the slip's end, and stops before the wall.
  const double mu = 0.5, press = 2.0, eps = 0.05, gap = 0.01;
  const argil::BSplineSurface tool = bowl_cap();
  const argil::BSplineSurface wall = wall_at(46.0 + gap);
  argil::HapticWorld w = world(argil::SurfaceToolShape{tool}, eps);
  REQUIRE(w.add_rigid(wavy_sheet(10, 10.0, 0.0), mu).ok());
  REQUIRE(w.add_rigid(wall, mu).ok());
  land(w, 40, 45, press);
  REQUIRE(w.proxy().in_contact);
  const double x0 = w.proxy().X_WT.p.x();  // the rim at x0 + 6, within eps of the wall
  REQUIRE(46.0 + gap - (x0 + 6.0) < 0.04);

  // Pressed along the contacts' normal and pulled along the surface towards
  // the wall past mu N: a slip of 0.045 mm. As the tick works it out, that
  // slip crosses the wall.
  const argil::Pose stick = w.proxy().X_WT;
  const Eigen::Vector3d n = w.proxy().outward_normal;
  const Eigen::Vector3d along = (Eigen::Vector3d::UnitX() - n.x() * n).normalized();
  const Eigen::Vector3d hand = stick.p + (mu * press + 0.045) * along - press * n;
  const argil::DeviceSample device = at(hand.x(), hand.y(), hand.z());
  const argil::FrictionOutcome fr = argil::coulomb_friction(device.X_WD.p - stick.p, n, mu, 1.0);
  REQUIRE_FALSE(fr.stick);
  REQUIRE(fr.slide.norm() == Approx(0.045).epsilon(1e-9));
  const argil::SurfaceHierarchy floor_h = w.hierarchy(0), wall_h = w.hierarchy(1);
  const std::vector<const argil::SurfaceHierarchy*> both{&floor_h, &wall_h};
  argil::OperatorCache cache;
  argil::SurfaceToolProxy check =
      argil::SurfaceToolProxy::create(tool, eps, cache, argil::WorldOptions{}.max_contacts).value();
  argil::Pose slid = stick;
  slid.p += fr.slide;
  const std::optional<argil::ToolContacts> swept = check.slip(both, stick, slid);
  REQUIRE(swept);
  REQUIRE(swept->crosses);

  const argil::TickResult r = w.step(device, 1e-3);
  REQUIRE(r.status.ok());
  CHECK_FALSE(check.crossing(both, r.proxy.X_WT).crosses);
  CHECK(r.proxy.in_contact);
  CHECK_FALSE(r.proxy.stuck);
  CHECK(r.proxy.X_WT.p.x() > x0);          // it slid towards the wall
  CHECK(r.proxy.X_WT.p.x() < 40.0 + gap);  // and stopped before it
  CHECK(r.force.x() < 0.0);                // the hand is held back
}

TEST_CASE("a B-spline tool whose slip longer than eps runs into a wall stops before it",
          "[haptic]") {
  // A slip longer than eps is not one swept query: the stick point is tested
  // (yes/no) and the tool moves from there to the slip's end, which here
  // lies past a wall 0.3 mm ahead of the cap's rim.
  const double mu = 0.5, press = 2.0, eps = 0.05, gap = 0.3;
  const argil::BSplineSurface tool = bowl_cap();
  const argil::BSplineSurface wall = wall_at(46.0 + gap);
  argil::HapticWorld w = world(argil::SurfaceToolShape{tool}, eps);
  REQUIRE(w.add_rigid(wavy_sheet(10, 10.0, 0.0), mu).ok());
  REQUIRE(w.add_rigid(wall, mu).ok());
  const double rest = land(w, 40, 45, press);
  REQUIRE(w.proxy().in_contact);
  REQUIRE(w.proxy().X_WT.p.x() == 40.0);

  // Pulled 1 mm past mu N towards the wall: the slip would put the rim
  // 0.7 mm into it.
  const argil::TickResult r = w.step(at(40 + mu * press + 1.0, 45, rest - press), 1e-3);
  REQUIRE(r.status.ok());
  const argil::SurfaceHierarchy floor_h = w.hierarchy(0), wall_h = w.hierarchy(1);
  argil::OperatorCache cache;
  argil::SurfaceToolProxy check =
      argil::SurfaceToolProxy::create(tool, eps, cache, argil::WorldOptions{}.max_contacts).value();
  CHECK_FALSE(check.crossing({&floor_h, &wall_h}, r.proxy.X_WT).crosses);
  CHECK(r.proxy.in_contact);
  CHECK_FALSE(r.proxy.stuck);
  // Stopped within eps of the wall (the rim at x + 6), touching it, and
  // within eps of the floor (the slide along the mean of the two normals
  // lifts it a little).
  CHECK(r.proxy.X_WT.p.x() > 40.0 + gap - eps);
  CHECK(r.proxy.X_WT.p.x() < 40.0 + gap);
  CHECK_FALSE(r.body_contacts[1].empty());
  CHECK(std::abs(r.proxy.X_WT.p.z() - rest) < eps);
  CHECK(r.force.x() < 0.0);  // the hand is held back
}

TEST_CASE("a B-spline tool whose long slip leaves the floor's edge moves on towards the hand",
          "[haptic]") {
  // The slip's end touches nothing (the floor ends under it): there is no
  // contact to hold the tool back by friction, so it goes on towards the
  // hand in the same tick, over the floor's edge.
  const double mu = 0.5, press = 2.0, eps = 0.05;
  argil::HapticWorld w = world(argil::SurfaceToolShape{bowl_cap()}, eps);
  REQUIRE(w.add_rigid(wavy_sheet(10, 10.0, 0.0), mu).ok());  // the floor ends at x = 90
  const double rest = land(w, 88, 45, press);
  REQUIRE(w.proxy().in_contact);
  REQUIRE(w.proxy().X_WT.p.x() == 88.0);

  // A slip of 4 mm puts the cap's lowest point 2 mm past the edge, where the
  // cap is 0.2 mm (4 eps) above the floor's edge.
  const double slip = 4.0;
  const argil::DeviceSample hand = at(88 + mu * press + slip, 45, rest - press);
  const argil::TickResult r = w.step(hand, 1e-3);
  REQUIRE(r.status.ok());
  const argil::SurfaceHierarchy floor_h = w.hierarchy(0);
  argil::OperatorCache cache;
  argil::SurfaceToolProxy check =
      argil::SurfaceToolProxy::create(bowl_cap(), eps, cache, argil::WorldOptions{}.max_contacts)
          .value();
  CHECK_FALSE(check.crossing({&floor_h}, r.proxy.X_WT).crosses);
  CHECK_FALSE(r.proxy.stuck);
  // Not left at the slip's end: lower, and nearer the hand.
  const Eigen::Vector3d slid(88 + slip, 45, rest);
  CHECK(r.proxy.X_WT.p.z() < rest - eps);
  CHECK((hand.X_WD.p - r.proxy.X_WT.p).norm() < (hand.X_WD.p - slid).norm() - eps);
}

TEST_CASE("friction outside [0, kMaxFriction] is refused for deformable and rigid bodies",
          "[haptic]") {
  argil::HapticWorld w = world(argil::SphereToolShape{5.0});
  for (const double mu : {-0.1, argil::kMaxFriction * 1.01, std::nan("")}) {
    const argil::Result<int> rigid = w.add_rigid(wavy_sheet(6, 10.0, 0.0), mu);
    const argil::Result<int> soft = w.add_deformable(wavy_sheet(6, 10.0, 0.0), {}, {}, mu);
    CHECK(rigid.status().code == argil::StatusCode::invalid_argument);
    CHECK(soft.status().code == argil::StatusCode::invalid_argument);
    CHECK(soft.status().message.find("friction") != std::string::npos);
  }
  CHECK(w.body_count() == 0);
  const argil::Result<int> edge = w.add_rigid(wavy_sheet(6, 10.0, 0.0), argil::kMaxFriction);
  REQUIRE(edge.ok());
  CHECK(w.friction(edge.value()) == argil::kMaxFriction);
}

TEST_CASE("a B-spline tool smaller than the tolerance is refused when the world is made",
          "[haptic]") {
  // The reported case: a tool 0.017 mm across at eps 0.05 mm touched nothing
  // and went through a flat floor to z = -5 with status ok. Now no world is
  // made with it, and the message names the tool's size and the tolerance.
  const argil::BSplineSurface tool = wavy_sheet(4, 0.004, 0.0);
  REQUIRE(argil::control_point_box(tool).diagonal() == Approx(0.017).epsilon(0.01));
  argil::WorldOptions o;
  o.tolerance = 0.05;
  const auto w = argil::HapticWorld::create(argil::SurfaceToolShape{tool}, o);
  REQUIRE_FALSE(w.ok());
  CHECK(w.status().code == argil::StatusCode::invalid_argument);
  CHECK_THAT(w.status().message, Catch::Contains("tool surface: a tool 0.01697") &&
                                     Catch::Contains("too small for the tolerance") &&
                                     Catch::Contains("tolerance 0.05 mm"));
  // The same tool at a tolerance it resolves stops on the floor.
  o.tolerance = 1e-3;
  auto fine = argil::HapticWorld::create(argil::SurfaceToolShape{tool}, o);
  REQUIRE(fine.ok());
  REQUIRE(fine.value().add_rigid(wavy_sheet(10, 10.0, 0.0), 0.0).ok());
  REQUIRE(fine.value().step(at(30, 40, 1.0), 1e-3).status.ok());
  argil::TickResult r;
  for (int t = 1; t <= 60; ++t) {
    r = fine.value().step(at(30, 40, 1.0 - 6.0 * t / 60.0), 1e-3);  // down to z = -5
    REQUIRE(r.status.ok());
  }
  CHECK(r.proxy.in_contact);
  CHECK(r.proxy.X_WT.p.z() > -1e-3);  // on the floor, not through it
  CHECK(r.force.z() > 1.0);
}

TEST_CASE("a collision query that fails stops the tool's move with its status", "[haptic]") {
  // A model surface 0.01 mm wide: a tolerance of 0.05 mm exceeds its size, so
  // the tool's queries against it are outside the documented range.
  argil::BSplineSurface tool = wavy_sheet(4, 4.0, 0.0);
  argil::OperatorCache cache;
  auto proxy =
      argil::SurfaceToolProxy::create(tool, 0.05, cache, argil::WorldOptions{}.max_contacts);
  REQUIRE(proxy.ok());
  const argil::SurfaceHierarchy tiny =
      argil::SurfaceHierarchy::build(wavy_sheet(4, 0.003, 0.0), cache).value();
  const argil::ToolMove m =
      proxy.value().move({&tiny}, argil::Pose::at({0, 0, 1}), argil::Pose::at({0, 0, -1}));
  CHECK_FALSE(m.status.ok());
  CHECK(m.status.code == argil::StatusCode::invalid_argument);
  CHECK(m.status.message.find("tolerance") != std::string::npos);
}

TEST_CASE("world options name the rejected max_contacts value", "[haptic]") {
  argil::WorldOptions o;
  o.max_contacts = -2;
  const auto w = argil::HapticWorld::create(argil::SphereToolShape{1.0}, o);
  REQUIRE_FALSE(w.ok());
  CHECK(w.status().message == "world.max_contacts must be at least 1, got -2");
}

TEST_CASE("set_tool changes the tool between strokes only; the new one rides on the surface",
          "[haptic]") {
  argil::HapticWorld w = world(argil::SphereToolShape{0.0});  // a point
  REQUIRE(w.add_rigid(wavy_sheet(10, 10.0, 0.0), 0.0).ok());
  REQUIRE(w.step(at(40, 40, 10), 1e-3).status.ok());
  REQUIRE(w.step(at(40, 40, -1), 1e-3).status.ok());  // engaged: a stroke
  const argil::Status refused = w.set_tool(argil::SphereToolShape{4.0});
  CHECK(refused.code == argil::StatusCode::failed_precondition);
  argil::DeviceSample released = at(40, 40, 10);
  released.engaged = false;
  REQUIRE(w.step(released, 1e-3).status.ok());
  // A bad radius is refused and the point stays.
  CHECK_FALSE(w.set_tool(argil::SphereToolShape{-1.0}).ok());
  REQUIRE(w.step(at(40, 40, 10), 1e-3).status.ok());
  REQUIRE(w.step(at(40, 40, -1), 1e-3).status.ok());
  CHECK(w.proxy().X_WT.p.z() == Approx(0.0).margin(0.02));
  released = at(40, 40, 10);
  released.engaged = false;
  REQUIRE(w.step(released, 1e-3).status.ok());
  // The ball rests one radius above the sheet.
  REQUIRE(w.set_tool(argil::SphereToolShape{4.0}).ok());
  REQUIRE(w.step(at(40, 40, 10), 1e-3).status.ok());
  const argil::TickResult r = w.step(at(40, 40, -1), 1e-3);
  REQUIRE(r.status.ok());
  CHECK(r.proxy.X_WT.p.z() == Approx(4.0).margin(0.02));
}

TEST_CASE("a B-spline tool follows a panel that gives way under it: the force never drops out",
          "[haptic]") {
  // A soft panel yields under the cap while the hand holds it 1 mm below
  // where it landed, then drags it along x at 20 um a tick (a slip shorter
  // than eps each tick). The panel flows away from the tool tick after tick;
  // the tool must come down with it, not hang where it was until the gap
  // passes eps, lose the contact and drop the force to zero.
  const double eps = 0.05;
  argil::HapticWorld w = cap_on_soft_panel(eps);
  const double landed = w.proxy().X_WT.p.z();
  std::vector<double> force;
  double sunk = 0.0;
  for (int t = 0; t < 400; ++t) {
    const double x = 45.0 + 0.02 * std::max(t - 100, 0);
    const argil::TickResult r = w.step(at(x, 45, landed - 1.0), 1e-3);
    REQUIRE(r.status.ok());
    CAPTURE(t);
    CHECK(r.proxy.in_contact);
    CHECK(r.max_depth >= -eps);  // within eps: a contact
    // It keeps off the edge of the contact: it aims at 3/4 eps after the
    // panel's step, allowing for half of how far the panel flowed in the tick
    // before (up to 20 um; 0.92 eps at worst, in the first ticks). A tool
    // left hanging stands off it by up to eps, then loses it.
    if (t > 0) CHECK(r.max_depth >= -0.95 * eps);
    force.push_back(r.force.norm());
    sunk = std::max(sunk, landed - r.proxy.X_WT.p.z());
  }
  CHECK(sunk > 0.2);  // the panel gave way, and the tool went down with it
  // The force eases off as the panel yields, without a step: no tick changes
  // it by 5% (a tool hanging until the gap passes eps drops it by a fifth).
  for (std::size_t t = 2; t < force.size(); ++t) {
    CAPTURE(t);
    CHECK(std::abs(force[t] - force[t - 1]) < 0.05 * force[t - 1]);
  }
}

TEST_CASE("a B-spline tool held on a panel yielding faster than it settles stays stuck on it",
          "[haptic]") {
  // The hand holds still 3 mm below where the cap landed on a soft panel, so
  // the panel flows away from the tool by over eps / 2 a tick. The settle
  // (3/4 eps, less half of the last tick's flow) then leaves the tool off
  // by up to eps, and on most of the first ticks (and now and then after)
  // it touches nothing where friction held it. It must settle on and stay stuck, not take a
  // frictionless move towards the hand: that move searches for its stop with a dozen queries and
  // does not report the tool stuck.
  const double eps = 0.05;
  argil::HapticWorld w = cap_on_soft_panel(eps);
  const argil::Pose landed = w.proxy().X_WT;
  double fastest = 0.0;  // the deepest the tool went in one tick
  for (int t = 0; t < 300; ++t) {
    const double before = w.proxy().X_WT.p.z();
    const argil::TickResult r = w.step(at(45, 45, landed.p.z() - 3.0), 1e-3);
    REQUIRE(r.status.ok());
    CAPTURE(t);
    CHECK(r.proxy.in_contact);
    CHECK(r.proxy.stuck);
    CHECK(r.proxy.X_WT.p.x() == landed.p.x());
    CHECK(r.proxy.X_WT.p.y() == landed.p.y());
    // One contact query a tick (two when it settles further), no crossing
    // test: the frictionless move searched for its stop with up to a dozen.
    CHECK(r.tool_contact_queries <= 2);
    CHECK(r.tool_crossing_tests == 0);
    fastest = std::max(fastest, before - r.proxy.X_WT.p.z());
  }
  // The panel did flow faster than one settle (3/4 eps) follows.
  CHECK(fastest > 0.8 * eps);
  CHECK(landed.p.z() - w.proxy().X_WT.p.z() > 2.0);
}

TEST_CASE("a B-spline tool follows a hand that rests on a floor or lifts off in one query",
          "[haptic]") {
  // Landed on a rigid floor and lifted eps / 4 a tick: the hand is never
  // deeper than where the settle would bring the tool, so nothing presses,
  // no friction holds it, and the tool goes to the hand with one swept
  // contact query (the stick point's query and then a move took two).
  const double eps = 0.05, press = 2.0;
  argil::HapticWorld w = world(argil::SurfaceToolShape{bowl_cap()}, eps);
  REQUIRE(w.add_rigid(wavy_sheet(10, 10.0, 0.0), 0.5).ok());
  const double rest = land(w, 45, 45, press);
  REQUIRE(w.proxy().in_contact);
  // The hand where the tool rests: no force, at the hand, one query.
  argil::TickResult r = w.step(at(45, 45, rest), 1e-3);
  REQUIRE(r.status.ok());
  CHECK(r.proxy.X_WT.p == Eigen::Vector3d(45, 45, rest));
  CHECK(r.force.norm() == 0.0);
  CHECK(r.proxy.in_contact);
  CHECK(r.tool_contact_queries == 1);
  CHECK(r.tool_crossing_tests == 0);
  bool left = false;
  for (int t = 1; t <= 8; ++t) {
    CAPTURE(t);
    const double z = rest + 0.25 * eps * t;
    r = w.step(at(45.001, 45, z), 1e-3);
    REQUIRE(r.status.ok());
    CHECK(r.proxy.X_WT.p == Eigen::Vector3d(45.001, 45, z));
    CHECK(r.force.norm() == 0.0);
    if (!left) {
      // Still in contact last tick: friction's part of the tick, one query.
      CHECK(r.tool_contact_queries == 1);
      CHECK(r.tool_crossing_tests == 0);
    }
    left = !r.proxy.in_contact;
  }
  CHECK(left);  // lifted clear of the floor
}

TEST_CASE(
    "a B-spline tool left farther off a yielding panel than it aims follows a hand just under it",
    "[haptic]") {
  // Held deep in a soft panel, the tool stands off it by more than the
  // settle aims at (3/4 eps at most) on most ticks. A hand then brought to a
  // micrometre under the tool does not press past where the settle would
  // bring the tool: no normal force, so the tool goes to the hand in one
  // swept query (before: the stick point's query, then a move).
  const double eps = 0.05;
  argil::HapticWorld w = cap_on_soft_panel(eps);
  const argil::Pose landed = w.proxy().X_WT;
  int tried = 0;
  for (int t = 0; t < 100 && tried < 5; ++t) {
    CAPTURE(t);
    if (-w.proxy().max_depth > 0.76 * eps) {
      const Eigen::Vector3d hand = w.proxy().X_WT.p - 1e-3 * w.proxy().outward_normal;
      const argil::TickResult r = w.step(at(hand.x(), hand.y(), hand.z()), 1e-3);
      REQUIRE(r.status.ok());
      CHECK(r.proxy.X_WT.p == hand);
      CHECK(r.force.norm() == 0.0);
      CHECK(r.tool_contact_queries == 1);
      CHECK(r.tool_crossing_tests == 0);
      ++tried;
    }
    REQUIRE(w.step(at(landed.p.x(), landed.p.y(), landed.p.z() - 3.0), 1e-3).status.ok());
  }
  CHECK(tried == 5);
}

TEST_CASE("a hand turning on past where the B-spline tool's rim meets a floor costs no extra query",
          "[haptic]") {
  // The hand rests at the tool and turns 0.02 rad a tick: the rim soon meets
  // the floor and the tool's turn is blocked, while the hand turns on. The
  // turned pose at the hand crosses, so following it in one query is not
  // tried (a wasted query a tick, five in the worst one): the stick point's
  // query and the move decide, at most four contact queries a tick.
  const double eps = 0.05;
  const argil::BSplineSurface tool = bowl_cap();
  argil::HapticWorld w = world(argil::SurfaceToolShape{tool}, eps);
  REQUIRE(w.add_rigid(wavy_sheet(10, 10.0, 0.0), 0.5).ok());
  land(w, 45, 45, 2.0);
  REQUIRE(w.proxy().in_contact);
  const argil::SurfaceHierarchy floor_h = w.hierarchy(0);
  argil::OperatorCache cache;
  argil::SurfaceToolProxy check =
      argil::SurfaceToolProxy::create(tool, eps, cache, argil::WorldOptions{}.max_contacts).value();
  const Eigen::Vector3d axis = Eigen::Vector3d(1, 0.3, 0).normalized();
  double blocked = 0.0;  // the largest angle between the hand and the tool
  for (int t = 1; t < 100; ++t) {
    CAPTURE(t);
    argil::Pose hand = w.proxy().X_WT;
    hand.R = Eigen::Quaterniond(Eigen::AngleAxisd(0.02 * t, axis));
    const argil::TickResult r =
        w.step({.tick = t, .t = 1e-3 * t, .X_WD = hand, .engaged = true}, 1e-3);
    REQUIRE(r.status.ok());
    CHECK(r.tool_contact_queries <= 4);
    CHECK_FALSE(check.crossing({&floor_h}, r.proxy.X_WT).crosses);
    blocked = std::max(blocked, hand.R.angularDistance(r.proxy.X_WT.R));
  }
  CHECK(blocked > 0.5);  // the turn was blocked, the hand turned on
}

TEST_CASE(
    "a B-spline tool whose settle would cross a panel springing back stays stuck where it was",
    "[haptic]") {
  // The cap rests on an elastic soft panel, the hand 3 mm below it. Every
  // other pair of ticks the hand eases off by 0.5 mm: the panel springs back
  // up into where the settle would bring the tool (the last tick left it
  // farther off than the settle aims). The settled stick point crosses; the
  // tool must fall back to its stick point as the last tick left it and
  // stay stuck there, not take a frictionless move towards the hand (three
  // contact queries and two crossing tests, and not stuck).
  const double eps = 0.05;
  argil::HapticWorld w = world(argil::SurfaceToolShape{bowl_cap()}, eps, 20.0);
  add_soft_panel(w, wavy_sheet(10, 10.0, 0.0), 1e9, 0.0);  // elastic, undamped
  REQUIRE(w.step(at(45, 45, 10), 1e-3).status.ok());
  for (int t = 0; t < 5 && !w.proxy().in_contact; ++t)
    REQUIRE(w.step(at(45, 45, -3.0), 1e-3).status.ok());
  REQUIRE(w.proxy().in_contact);
  const argil::Pose landed = w.proxy().X_WT;
  int held = 0, fell_back = 0;
  for (int t = 0; t < 120; ++t) {
    const bool eased = (t / 2) % 2 == 1;
    const Eigen::Vector3d before = w.proxy().X_WT.p;
    const argil::TickResult r = w.step(at(45, 45, landed.p.z() - 3.0 + (eased ? 0.5 : 0.0)), 1e-3);
    REQUIRE(r.status.ok());
    CAPTURE(t);
    CHECK(r.proxy.in_contact);
    CHECK(r.max_depth <= eps);
    CHECK(r.proxy.X_WT.p.x() == landed.p.x());
    CHECK(r.proxy.X_WT.p.y() == landed.p.y());
    // The second tick of a held hand, eased or not, once the tool has come
    // down from its landing (two ticks): stuck, in two queries.
    if (t >= 2 && t % 2 == 1) {
      CHECK(r.proxy.stuck);
      CHECK(r.tool_contact_queries <= 2);
      CHECK(r.tool_crossing_tests == 0);
      held += r.proxy.stuck ? 1 : 0;
    }
    // Where the settle crossed, the tool stays exactly where the last tick
    // left it (settled, or settled further, it comes down).
    if (t >= 2 && r.proxy.stuck && r.proxy.X_WT.p == before) ++fell_back;
  }
  CHECK(held == 59);
  CHECK(fell_back >= 20);  // the second eased tick, each time (29 of them)
}

TEST_CASE(
    "a B-spline tool whose short slip ends clear of a panel flowing away settles on from there",
    "[haptic]") {
  // The hand 3 mm under the cap drags it 20 um a tick (a slip shorter than
  // eps) over a soft panel that flows away from the tool faster than it
  // settles. On about ten of the ticks the slip ends touching nothing; the
  // tool must settle on from where it slid (one more swept query), not take
  // a frictionless move towards the hand, which searches for its stop with
  // four crossing tests and four contact queries.
  const double eps = 0.05;
  argil::HapticWorld w = cap_on_soft_panel(eps);
  const argil::Pose landed = w.proxy().X_WT;
  int settled_on = 0;
  for (int t = 0; t < 300; ++t) {
    const double x = landed.p.x() + 0.02 * t;
    const argil::TickResult r = w.step(at(x, landed.p.y(), landed.p.z() - 3.0), 1e-3);
    REQUIRE(r.status.ok());
    CAPTURE(t);
    CHECK(r.proxy.in_contact);
    CHECK(r.max_depth >= -eps);
    CHECK(r.tool_contact_queries <= 2);
    CHECK(r.tool_crossing_tests == 0);
    // Slipping, the slip's query and the settle's: two.
    if (!r.proxy.stuck && r.tool_contact_queries == 2) ++settled_on;
  }
  CHECK(settled_on > 0);
}
