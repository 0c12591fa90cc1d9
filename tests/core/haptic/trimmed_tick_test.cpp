// Contact only with material in the haptic tick: a sphere or point over a
// hole touches nothing and drops through; dragged across a trimmed edge it
// rolls over the edge and leaves it; contacts never lie outside the trims.
// The plate is u/v-asymmetric (degree 3 x 2, 7 x 5 poles) with x = 90 u and
// y = 90 v exactly, so trims in (u, v) are the same shapes in millimetres.
#include <catch2/catch.hpp>
#include <cmath>

#include "argil/core.hpp"
#include "support/trim_loops.hpp"

namespace argil {
namespace {

constexpr double kSize = 90.0;  // the plate is 90 mm square, z = 0
constexpr double kEps = 0.01;

HapticWorld world_with(double radius) {
  WorldOptions o;
  o.tolerance = kEps;
  o.coupling = {.stiffness = 1.0, .damping = 0.0, .max_force = 100.0};
  Result<HapticWorld> w = HapticWorld::create(SphereToolShape{radius}, o);
  REQUIRE(w.ok());
  return std::move(w).value();
}

DeviceSample device_at(const Eigen::Vector3d& p) {
  return {.tick = 0, .t = 0.0, .X_WD = Pose::at(p), .engaged = true};
}

Eigen::Vector2d uv_of(double x, double y) { return {x / kSize, y / kSize}; }

/// The plate with a round hole of `radius` [mm] around (45, 45).
TrimRegion holed(double radius) {
  const std::vector<TrimLoop> loops{
      test::rectangle_loop({0, 0}, {1, 1}, true),
      test::ellipse_loop(uv_of(45, 45), radius / kSize, radius / kSize, false)};
  return TrimRegion::create(loops).value();
}

/// A bowl-shaped cap 12 mm across, lowest at its frame origin (z = 0.05 r^2).
BSplineSurface small_cap() {
  BSplineSurface cap = test::asymmetric_plate(12.0, 0.0);
  for (Eigen::Index k = 0; k < cap.control_points.rows(); ++k) {
    const double x = cap.control_points(k, 0) - 6.0, y = cap.control_points(k, 1) - 6.0;
    cap.control_points.row(k) << x, y, 0.05 * (x * x + y * y);
  }
  return cap;
}

/// The plate cut at x = `edge` [mm]: material for x <= edge.
TrimRegion cut_at(double edge) {
  return TrimRegion::create({test::rectangle_loop({0, 0}, {edge / kSize, 1}, true)}).value();
}

}  // namespace

TEST_CASE("a sphere or point pressed on a hole touches nothing and drops through",
          "[haptic][trim]") {
  for (const double radius : {5.0, 0.0}) {
    for (const bool trimmed : {true, false}) {
      CAPTURE(radius, trimmed);
      HapticWorld w = world_with(radius);
      const int body = w.add_rigid(test::asymmetric_plate(kSize, 0.0), 0.3).value();
      if (trimmed) REQUIRE(w.set_trim(body, holed(15.0)).ok());
      int contacts = 0;
      TickResult r;
      for (int k = 0; k <= 100; ++k) {  // 20 mm above to 30 mm below, 0.5 mm a tick
        r = w.step(device_at({45.0, 45.0, 20.0 - 0.5 * k}), 1e-3);
        REQUIRE(r.status.ok());
        contacts += r.contacts;
      }
      if (trimmed) {
        CHECK(contacts == 0);
        CHECK((r.proxy.X_WT.p - Eigen::Vector3d(45, 45, -30)).norm() < 1e-9);  // with the hand
        CHECK(r.force.norm() < 1e-9);
      } else {
        // The same press on the whole plate is held on top: the test can fail.
        CHECK(contacts > 0);
        CHECK(r.proxy.X_WT.p.z() > radius - kEps);
      }
    }
  }
}

TEST_CASE("a sphere dragged across a trimmed edge rolls over it and stops touching",
          "[haptic][trim]") {
  const double radius = 5.0, edge = 45.0;
  const TrimRegion region = cut_at(edge);
  for (const bool deformable : {false, true}) {
    CAPTURE(deformable);
    HapticWorld w = world_with(radius);
    const Material clay = *argil::material_preset("clay");
    const BSplineSurface plate = test::asymmetric_plate(kSize, 0.0);
    const int body = deformable ? w.add_deformable(plate, clay, {}, 0.0).value()
                                : w.add_rigid(plate, 0.0).value();
    REQUIRE(w.set_trim(body, region).ok());
    REQUIRE(w.step(device_at({20, 45, 20}), 1e-3).status.ok());
    double last_touch_x = -1.0, deepest = 0.0;
    int edge_contacts = 0, touching_ticks = 0;
    for (int k = 0; k <= 600; ++k) {  // x from 20 to 80 mm, 0.1 mm a tick, pressing 1 mm
      const double x = 20.0 + 0.1 * k;
      const TickResult r = w.step(device_at({x, 45, radius - 1.0}), 1e-3);
      REQUIRE(r.status.ok());
      deepest = std::max(deepest, r.max_depth);
      for (const Contact& c : r.body_contacts[0]) {
        CAPTURE(x, c.uv_a.x(), c.point.x());
        CHECK(c.depth <= kEps);
        // Never beyond the edge: a contact is material, or on the edge itself.
        CHECK(c.point.x() <= edge + kEps);
        if (!region.contains(c.uv_a)) {
          ++edge_contacts;
          CHECK(c.uv_a.x() == Approx(edge / kSize).margin(1e-9));
        }
      }
      if (r.contacts > 0) {
        ++touching_ticks;
        last_touch_x = r.proxy.X_WT.p.x();
        // Rolling over the edge of the rigid plate: the centre stays a radius
        // from the material (the nearest of the plate's points with x <= edge).
        const Eigen::Vector3d nearest(std::min(r.proxy.X_WT.p.x(), edge), 45.0, 0.0);
        if (!deformable) CHECK((r.proxy.X_WT.p - nearest).norm() >= radius - kEps);
      }
      if (x > edge + radius + 2.0) {
        CHECK(r.contacts == 0);  // past the edge the hand is free
        CHECK((r.proxy.X_WT.p - Eigen::Vector3d(x, 45, radius - 1.0)).norm() < 1e-6);
      }
    }
    CHECK(touching_ticks > 200);
    CHECK(edge_contacts > 0);    // it did touch the edge itself
    CHECK(last_touch_x > edge);  // and rolled past it
    CHECK(last_touch_x <= edge + radius + kEps);
    CHECK(deepest <= kEps);
  }
}

TEST_CASE("set_trim refuses an unknown body and trims that miss the domain", "[haptic][trim]") {
  HapticWorld w = world_with(2.0);
  const int body = w.add_rigid(test::asymmetric_plate(kSize, 0.0), 0.3).value();
  const Status unknown = w.set_trim(3, holed(10.0));
  CHECK(unknown.code == StatusCode::invalid_argument);
  CHECK(unknown.message == "set_trim: body 3 is not in [0, 1)");
  const TrimRegion far = TrimRegion::create({test::rectangle_loop({5, 5}, {6, 6}, true)}).value();
  const Status missing = w.set_trim(body, far);
  CHECK(missing.code == StatusCode::invalid_argument);
  CHECK_THAT(missing.message, Catch::Contains("misses the surface's domain [0, 1] x [0, 1]"));
  CHECK(w.trim(body).empty());
  REQUIRE(w.set_trim(body, holed(10.0)).ok());
  CHECK_FALSE(w.trim(body).empty());
  REQUIRE(w.set_trim(body, TrimRegion()).ok());  // back to untrimmed
  CHECK(w.trim(body).empty());
}

TEST_CASE("the B-spline tool's contacts outside the trims are dropped", "[haptic][trim]") {
  // Pressed onto the plate inside a hole and on material. The advance still
  // stops it on the whole surface: only its contacts follow the trims.
  const BSplineSurface tool = small_cap();
  for (const double x : {45.0, 20.0}) {  // in the hole, then on material
    CAPTURE(x);
    WorldOptions o;
    o.tolerance = 0.05;
    HapticWorld w = HapticWorld::create(SurfaceToolShape{tool}, o).value();
    const int body = w.add_rigid(test::asymmetric_plate(kSize, 0.0), 0.0).value();
    REQUIRE(w.set_trim(body, holed(15.0)).ok());
    REQUIRE(w.step(device_at({x, 45, 5}), 1e-3).status.ok());
    TickResult r;
    for (int k = 0; k < 10; ++k) r = w.step(device_at({x, 45, -2}), 1e-3);
    REQUIRE(r.status.ok());
    for (const Contact& c : r.body_contacts[0]) CHECK(w.trim(body).contains(c.uv_a));
    CHECK((r.contacts > 0) == (x == 20.0));
  }
}

TEST_CASE("the B-spline tool slides over a hole along the whole surface that holds it up",
          "[haptic][trim]") {
  // Held up in a hole by the trimmed-away plate (no contact, no force on the
  // body), the cap is dragged 5 mm along it: it slides with the hand (the
  // normal it slides along is the whole surface's), without contacts.
  WorldOptions o;
  o.tolerance = 0.05;
  HapticWorld w = HapticWorld::create(SurfaceToolShape{small_cap()}, o).value();
  const int body = w.add_rigid(test::asymmetric_plate(kSize, 0.0), 0.0).value();
  REQUIRE(w.set_trim(body, holed(15.0)).ok());
  REQUIRE(w.step(device_at({45, 45, 5}), 1e-3).status.ok());
  for (int k = 0; k < 10; ++k) REQUIRE(w.step(device_at({45, 45, -2}), 1e-3).status.ok());
  const double rest = w.proxy().X_WT.p.z();  // held up by the plate
  REQUIRE(rest > -2.0);
  TickResult r;
  for (int k = 1; k <= 10; ++k) {
    r = w.step(device_at({45.0 + 0.5 * k, 45, -2}), 1e-3);
    REQUIRE(r.status.ok());
    CHECK(r.contacts == 0);
  }
  CHECK(r.proxy.X_WT.p.x() == Approx(50.0).margin(o.tolerance));
  CHECK(r.proxy.X_WT.p.z() == Approx(rest).margin(o.tolerance));
  CHECK(w.proxy().outward_normal.z() == Approx(1.0).epsilon(1e-9));
}

TEST_CASE("the B-spline tool keeps max_contacts contacts on the material beside a trimmed edge",
          "[haptic][trim]") {
  // The plate is cut at x = 45 and the cap pressed just beyond the cut: its
  // deepest contacts lie off the material. Kept to max_contacts after those
  // are set apart, it keeps as many as it has on the material, up to
  // max_contacts, whatever the world's option.
  const auto material_contacts = [](int max_contacts) {
    WorldOptions o;
    o.tolerance = 0.05;
    o.max_contacts = max_contacts;
    HapticWorld w = HapticWorld::create(SurfaceToolShape{small_cap()}, o).value();
    const int body = w.add_rigid(test::asymmetric_plate(kSize, 0.0), 0.0).value();
    REQUIRE(w.set_trim(body, cut_at(45.0)).ok());
    REQUIRE(w.step(device_at({45.6, 45, 5}), 1e-3).status.ok());
    TickResult r;
    for (int k = 0; k < 10; ++k) r = w.step(device_at({45.6, 45, -2}), 1e-3);
    REQUIRE(r.status.ok());
    for (const Contact& c : r.body_contacts[0]) CHECK(w.trim(body).contains(c.uv_a));
    return static_cast<int>(r.body_contacts[0].size());
  };
  const int all = material_contacts(100000);
  CAPTURE(all);
  REQUIRE(all >= 8);  // twice the cap below: the cap, not the material, decides
  CHECK(material_contacts(4) == 4);
}

}  // namespace argil
