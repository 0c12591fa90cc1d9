// Sleep and reach (docs/deformation.md): bodies out of the tool's reach are
// left out of its queries, and a settled deformable body out of reach is not
// stepped; neither changes a single bit of what the tool feels.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "argil/core.hpp"
#include "support/random_surface.hpp"
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
argil::HapticWorld sphere_world(bool sleep, bool cull, double radius = kRadius) {
  argil::WorldOptions o;
  o.tolerance = kEps;
  o.coupling = {.stiffness = 1.0, .damping = 0.0, .max_force = 100.0};
  o.sleep = sleep;
  o.cull = cull;
  auto w = argil::HapticWorld::create(argil::SphereToolShape{radius}, o);
  REQUIRE(w.ok());
  return std::move(w).value();
}

/// The world under test (sleep and cull as given) and the reference where
/// every body is queried and stepped, built alike by `build`.
struct Worlds {
  argil::HapticWorld tested;
  argil::HapticWorld reference;
};

template <class Build>
Worlds worlds(bool sleep, bool cull, const Build& build, double radius = kRadius) {
  Worlds w{sphere_world(sleep, cull, radius), sphere_world(false, false, radius)};
  build(w.tested);
  build(w.reference);
  return w;
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
    Worlds w = worlds(true, true, [](argil::HapticWorld& x) { add_panel(x, {0, 0, 0}); });
    argil::HapticWorld& sleeping = w.tested;
    argil::HapticWorld& reference = w.reference;
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
  Worlds w = worlds(false, true, add_row);
  argil::HapticWorld& culled = w.tested;
  argil::HapticWorld& reference = w.reference;
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
  Worlds w = worlds(true, true, add_row);
  argil::HapticWorld& sleeping = w.tested;
  argil::HapticWorld& reference = w.reference;
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

namespace {

/// Farthest the proxy moves in one tick [mm]: SphereProxy::move takes at
/// most kMaxSubsteps substeps of max(r/2, 10 eps) and stops short of a
/// device farther away, so a faster device only leaves the proxy behind.
double max_speed(double radius) {
  return argil::SphereProxy::kMaxSubsteps * std::max(0.5 * radius, 10.0 * kEps);
}

/// `s` turned by `R` about the origin, then moved by `t`.
argil::BSplineSurface placed(argil::BSplineSurface s, const Eigen::AngleAxisd& R,
                             const Eigen::Vector3d& t) {
  const Eigen::Matrix3d m = R.toRotationMatrix();
  for (Eigen::Index k = 0; k < s.control_points.rows(); ++k)
    s.control_points.row(k) = (m * s.control_points.row(k).transpose() + t).transpose();
  return s;
}

/// Sleeping targets of several sizes and orientations: deformable panels of
/// 10, 30 and 4 mm, the curved rational asymmetric face (60 x 30 mm, a double
/// knot), and two rigid faces (a panel and the polynomial asymmetric face).
void add_targets(argil::HapticWorld& w) {
  argil::BoundaryConditions held;
  held.fixed_u0 = true;
  const auto deformable = [&](const argil::BSplineSurface& s) {
    REQUIRE(w.add_deformable(s, argil::Material{}, held, 0.3).ok());
  };
  const auto axis = [](double x, double y, double z) {
    return Eigen::Vector3d(x, y, z).normalized();
  };
  deformable(argil::test::flat_bicubic_panel(10.0, 5));
  deformable(placed(argil::test::flat_bicubic_panel(30.0, 6), Eigen::AngleAxisd(0.6, axis(1, 1, 0)),
                    {50, -10, 5}));
  deformable(placed(argil::test::flat_bicubic_panel(4.0, 3),
                    Eigen::AngleAxisd(1.2, axis(0, 1, 0.3)), {-5, 40, 8}));
  deformable(placed(argil::test::asymmetric_surface(true),
                    Eigen::AngleAxisd(-0.4, axis(0.2, 0.1, 1)), {-80, -20, 0}));
  REQUIRE(w.add_rigid(placed(argil::test::flat_bicubic_panel(20.0, 4),
                             Eigen::AngleAxisd(2.0, axis(1, 0, 0)), {10, -50, 0}),
                      0.3)
              .ok());
  REQUIRE(w.add_rigid(placed(argil::test::asymmetric_surface(false),
                             Eigen::AngleAxisd(2.5, axis(0.3, 1, 0.2)), {60, 60, -10}),
                      0.3)
              .ok());
}

/// A straight stroke of the device at `speed` mm per tick from `start` to
/// `end`, where it then holds.
struct Stroke {
  double radius = kRadius;  // of the sphere tool [mm]
  double speed = 0.0;       // [mm per tick]
  Eigen::Vector3d start = Eigen::Vector3d::Zero();
  Eigen::Vector3d end = Eigen::Vector3d::Zero();
  int body = 0;        // the body it aims at
  bool graze = false;  // passes beside an edge of the body, touching it or not

  /// The device at tick k of the stroke (k = 0: at the start).
  Eigen::Vector3d at(int k) const {
    const double length = (end - start).norm();
    return start + std::min(k * speed, length) / length * (end - start);
  }
  int ticks_to_end() const { return static_cast<int>(std::ceil((end - start).norm() / speed)); }
};

double distance_to_box(const Eigen::Vector3d& p, const argil::Box3& box) {
  return (p - p.cwiseMax(box.min).cwiseMin(box.max)).norm();
}

/// A random stroke of `w`'s bodies at the proxy's top speed for a sphere of
/// 2 or 0.5 mm or a point: towards a random point of a random body (in the
/// middle half of its domain), 1 mm through it, from 1.5 to 4.5 ticks away
/// (out of reach of every body); one in five instead runs along the body's
/// normal beside an edge, its centre between r - eps and r + 3 eps from it,
/// past the face or to a stop level with the edge.
Stroke random_stroke(const argil::HapticWorld& w, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> normal(0.0, 1.0);
  Stroke s;
  const double radii[] = {kRadius, 0.5, 0.0};
  s.radius = radii[std::uniform_int_distribution<int>(0, 2)(rng)];
  s.speed = max_speed(s.radius);
  s.body = std::uniform_int_distribution<int>(0, w.body_count() - 1)(rng);
  const argil::BSplineSurface& f = w.surface(s.body);
  const auto param = [&](argil::Direction d, double x) {
    return f.domain_start(d) + x * (f.domain_end(d) - f.domain_start(d));
  };
  s.graze = unit(rng) < 0.2;
  for (;;) {
    Eigen::Vector3d target, direction;
    double beyond = 1.0;  // [mm] past the target
    if (s.graze) {
      // An edge u = u0 or u1, v = v0 or v1; outward: along -S_u, S_u, -S_v or S_v.
      const int edge = std::uniform_int_distribution<int>(0, 3)(rng);
      const double along = 0.1 + 0.8 * unit(rng);
      const double u =
          edge < 2 ? param(argil::Direction::u, edge) : param(argil::Direction::u, along);
      const double v =
          edge < 2 ? param(argil::Direction::v, along) : param(argil::Direction::v, edge - 2);
      const argil::SurfaceDerivatives d = argil::evaluate_derivatives(f, u, v, 1);
      const Eigen::Vector3d n = argil::unit_normal(d);
      Eigen::Vector3d out = edge < 2 ? Eigen::Vector3d((edge == 0 ? -1.0 : 1.0) * d.du)
                                     : Eigen::Vector3d((edge == 2 ? -1.0 : 1.0) * d.dv);
      out = (out - out.dot(n) * n).normalized();
      target = d.point + (s.radius + kEps * (4.0 * unit(rng) - 1.0)) * out;
      direction = (unit(rng) < 0.5 ? 1.0 : -1.0) * n;
      // Past the face altogether (contacts only in the substeps of a tick,
      // where the push-out bends the path by up to eps), or to a stop beside it.
      beyond = unit(rng) < 0.5 ? s.radius + 5.0 : 0.0;
    } else {
      // Inside the middle half of the domain and no flatter than 60 degrees
      // off the face: the device ends behind the face, not beyond its edge,
      // where the proxy could slip round it.
      const double u = param(argil::Direction::u, 0.25 + 0.5 * unit(rng));
      const double v = param(argil::Direction::v, 0.25 + 0.5 * unit(rng));
      target = argil::evaluate(f, u, v);
      const Eigen::Vector3d n = (unit(rng) < 0.5 ? 1.0 : -1.0) * argil::unit_normal(f, u, v);
      direction = (n + 0.8 * Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized())
                      .normalized();
      if (direction.dot(n) < 0.5) continue;
    }
    s.start = target + (1.5 + 3.0 * unit(rng)) * s.speed * direction;
    s.end = target - beyond * direction;
    bool clear = true;  // the start is out of every body's reach
    for (int b = 0; b < w.body_count(); ++b)
      clear = clear &&
              distance_to_box(s.start, argil::control_point_box(w.surface(b))) > s.radius + 10.0;
    if (clear) return s;
  }
}

/// Ticks of a world that sleeps and culls beside the reference, compared bit
/// for bit. A body the tool touched may fall asleep again once it settled out
/// of reach, within kSleepFraction eps of its rest shape where the reference
/// keeps creeping towards it (the rest-threshold test above): their bits part
/// from the tick after, so the comparison ends there.
struct Lockstep {
  Worlds& w;
  std::vector<char> touched = std::vector<char>(static_cast<std::size_t>(w.tested.body_count()), 0);
  bool resleep = false;  // a touched body is asleep again: no more comparing

  /// One tick of both with the device at `device`; the tested world's result.
  argil::TickResult step(const argil::DeviceSample& device) {
    REQUIRE_FALSE(resleep);
    argil::TickResult a = w.tested.step(device, kDt);
    const argil::TickResult b = w.reference.step(device, kDt);
    require_identical(a, b, w.tested, w.reference);
    for (std::size_t k = 0; k < touched.size(); ++k) {
      CAPTURE(k);
      // Woken in time: a body is awake on every tick it is touched.
      if (!a.body_contacts[k].empty()) REQUIRE_FALSE(w.tested.asleep(static_cast<int>(k)));
      touched[k] = touched[k] || !a.body_contacts[k].empty();
      resleep = resleep || (touched[k] && w.tested.asleep(static_cast<int>(k)));
    }
    return a;
  }
};

/// A stroke through a world that sleeps and culls and through the
/// reference, after three ticks at the start that put every deformable body
/// to sleep: both worlds first touch a body on the same tick, and every
/// tick's result and control points match to the bit up to `after_contact`
/// ticks past it (or a touched body's return to sleep, Lockstep).
struct StrokeOutcome {
  int first_contact = -1;  // tick of the first contact, -1: none
  bool resleep = false;    // the comparison ended early at a touched body's sleep
};

StrokeOutcome compare_stroke(Worlds& w, const Stroke& s, int after_contact) {
  Lockstep lock{w};
  for (int k = 0; k < 3; ++k) (void)lock.step(at(s.start));
  for (int b = 0; b < w.tested.body_count(); ++b)
    REQUIRE(w.tested.asleep(b) != w.tested.is_rigid(b));
  StrokeOutcome out;
  int first_reference = -1;
  const int last = s.ticks_to_end() + after_contact;
  for (int k = 1; k <= last && !lock.resleep; ++k) {
    CAPTURE(k);
    const argil::TickResult a = lock.step(at(s.at(k)));
    if (a.contacts > 0 && out.first_contact < 0) out.first_contact = k;
    if (w.reference.proxy().in_contact && first_reference < 0) first_reference = k;
    REQUIRE(out.first_contact == first_reference);
    if (out.first_contact >= 0 && k >= out.first_contact + after_contact) break;
  }
  out.resleep = lock.resleep;
  return out;
}

}  // namespace

TEST_CASE(
    "sleep: strokes at the top speed onto sleeping bodies first touch on the never-sleeping "
    "world's tick, to the bit",
    "[haptic][sleep][slow]") {
  // 60 seeded strokes from out of every body's reach towards random points of
  // six sleeping bodies (4 to 60 mm, turned, curved, rational, rigid) and
  // beside their edges, at the proxy's top speed (256 substeps a tick: 256 mm
  // for the 2 mm sphere, 64 mm for the 0.5 mm one, 25.6 mm for the point).
  std::mt19937_64 rng(13);
  argil::HapticWorld layout = sphere_world(true, true);
  add_targets(layout);
  int touched = 0, grazed = 0, missed = 0, resleeps = 0;
  for (int stroke = 0; stroke < 60; ++stroke) {
    CAPTURE(stroke);
    const Stroke s = random_stroke(layout, rng);
    Worlds w = worlds(true, true, add_targets, s.radius);
    CAPTURE(s.radius, s.speed, s.body, s.graze);
    INFO("start " << s.start.transpose() << ", end " << s.end.transpose());
    const StrokeOutcome r = compare_stroke(w, s, 20);
    touched += r.first_contact >= 0 ? 1 : 0;
    resleeps += r.resleep ? 1 : 0;
    if (s.graze)
      (r.first_contact >= 0 ? grazed : missed) += 1;
    else
      CHECK(r.first_contact >= 0);  // a stroke 1 mm through a body touches it
  }
  std::printf("%d of 60 strokes touched (%d of their grazes), %d ended at a touched body's sleep\n",
              touched, grazed, resleeps);
  CHECK(grazed > 0);  // an edge touched in passing
  CHECK(missed > 0);  // and one passed by within 3 eps
}

namespace {

/// An open box of 10 mm panels: a deformable floor and three deformable
/// walls, and a rigid fourth wall.
void add_box(argil::HapticWorld& w) {
  argil::BoundaryConditions held;
  held.fixed_u0 = true;
  const argil::BSplineSurface panel = argil::test::flat_bicubic_panel(10.0, 5);
  const Eigen::AngleAxisd none(0.0, Eigen::Vector3d::UnitX());
  const Eigen::AngleAxisd x_wall(-0.5 * M_PI, Eigen::Vector3d::UnitY());  // (x, y) -> (0, y, x)
  const Eigen::AngleAxisd y_wall(0.5 * M_PI, Eigen::Vector3d::UnitX());   // (x, y) -> (x, 0, y)
  for (const auto& [R, t] :
       {std::pair{none, Eigen::Vector3d(0, 0, 0)}, std::pair{x_wall, Eigen::Vector3d(0, 0, 0)},
        std::pair{x_wall, Eigen::Vector3d(10, 0, 0)}, std::pair{y_wall, Eigen::Vector3d(0, 0, 0)}})
    REQUIRE(w.add_deformable(placed(panel, R, t), argil::Material{}, held, 0.3).ok());
  REQUIRE(w.add_rigid(placed(panel, y_wall, {0, 10, 0}), 0.3).ok());
}

}  // namespace

TEST_CASE(
    "sleep: every body asleep and then woken gives the never-sleeping world's ticks to the bit",
    "[haptic][sleep]") {
  Worlds w = worlds(true, true, add_box);
  Lockstep lock{w};
  const Eigen::Vector3d far(5, 5, 300);
  // Let go far above: every deformable body settles (it is at rest) and sleeps.
  for (int t = 0; t < 5; ++t) (void)lock.step(at(far, false));
  for (int b = 0; b < w.tested.body_count(); ++b) {
    CAPTURE(b);
    REQUIRE(w.tested.asleep(b) != w.tested.is_rigid(b));
    REQUIRE_FALSE(w.reference.asleep(b));
  }
  // In at the top speed into a corner where three bodies meet, then along
  // the floor to the opposite corner, where the other two meet it.
  std::vector<Eigen::Vector3d> device = {far};
  const auto go = [&](const Eigen::Vector3d& to, double speed) {
    const Eigen::Vector3d from = device.back();
    const int n = static_cast<int>(std::ceil((to - from).norm() / speed));
    for (int k = 1; k <= n; ++k) device.push_back(from + (to - from) * k / n);
  };
  go({1.5, 1.5, 1.5}, max_speed(kRadius));
  go({8.5, 8.5, 1.5}, 3.0);
  for (int k = 0; k < 20; ++k) device.push_back(device.back());
  std::size_t t = 0;
  for (; t < device.size() && !lock.resleep; ++t) {
    CAPTURE(t);
    (void)lock.step(at(device[t]));
  }
  std::printf("every body woken: compared %zu of %zu ticks\n", t, device.size());
  for (std::size_t k = 0; k < lock.touched.size(); ++k) {
    CAPTURE(k);
    CHECK(lock.touched[k]);  // every body woke and was pressed
  }
}
