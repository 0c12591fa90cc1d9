// The B-spline tool's proxy on its own (docs/deformation.md, B-spline tools):
// a move stops within eps / 2 of crossing, never crosses, and the contacts it
// returns are the contact query's at the pose where it stopped.
#include <catch2/catch.hpp>
#include <cmath>

#include "argil/core.hpp"
#include "support/tool_shapes.hpp"

namespace {

using argil::test::bowl_cap;
using argil::test::wavy_sheet;

constexpr double kEps = 0.05;
const int kMaxContacts = argil::WorldOptions{}.max_contacts;  // as a world keeps

struct Fixture {
  argil::OperatorCache cache;
  argil::SurfaceToolProxy proxy =
      argil::SurfaceToolProxy::create(bowl_cap(), kEps, cache, kMaxContacts).value();
  argil::SurfaceHierarchy flat =
      argil::SurfaceHierarchy::build(wavy_sheet(10, 10.0, 0.0), cache).value();
  argil::SurfaceHierarchy wavy =
      argil::SurfaceHierarchy::build(wavy_sheet(10, 10.0, 1.0), cache).value();
};

/// The move's contacts are the contact query's at its end, contact by contact.
void check_contacts_at_end(argil::SurfaceToolProxy& proxy,
                           const std::vector<const argil::SurfaceHierarchy*>& surfaces,
                           const argil::ToolMove& m) {
  const argil::ToolContacts at = proxy.contacts(surfaces, m.X_WT);
  REQUIRE(at.status.ok());
  CHECK(m.contacts.crosses == at.crosses);
  REQUIRE(m.contacts.per_surface.size() == at.per_surface.size());
  for (std::size_t b = 0; b < at.per_surface.size(); ++b) {
    REQUIRE(m.contacts.per_surface[b].size() == at.per_surface[b].size());
    for (std::size_t c = 0; c < at.per_surface[b].size(); ++c)
      CHECK((m.contacts.per_surface[b][c].point - at.per_surface[b][c].point).norm() <= 1e-12);
  }
  CHECK((m.contacts.outward_normal - at.outward_normal).norm() <= 1e-12);
}

}  // namespace

TEST_CASE("a B-spline tool moved onto a floor stops within eps / 2 of crossing it", "[haptic]") {
  Fixture f;
  const std::vector<const argil::SurfaceHierarchy*> floor{&f.flat};
  // Straight down from 5 mm and from 60 mm above (two substeps of at most
  // 4.3 mm, then sixteen) to where the cap would be 0.8 mm into the floor
  // (its lowest point is 1.2 mm above its origin): no slide, so the search's
  // stop is the move's end.
  for (const double above : {5.0, 60.0}) {
    for (const double x : {20.0, 43.0, 61.5}) {
      const argil::ToolMove m =
          f.proxy.move(floor, argil::Pose::at({x, 40.0, above}), argil::Pose::at({x, 40.0, -2.0}));
      REQUIRE(m.status.ok());
      CHECK(m.X_WT.p.x() == x);
      CHECK_FALSE(f.proxy.crossing(floor, m.X_WT).crosses);
      // Lowered by eps / 2 it crosses: the stop is that close to the floor.
      argil::Pose lower = m.X_WT;
      lower.p.z() -= 0.5 * kEps + 1e-9;
      CHECK(f.proxy.crossing(floor, lower).crosses);
      CHECK_FALSE(m.contacts.per_surface[0].empty());
      check_contacts_at_end(f.proxy, floor, m);

      // Pressed further from where it rests, it is blocked at once.
      const argil::ToolMove again = f.proxy.move(floor, m.X_WT, argil::Pose::at({x, 40.0, -2.0}),
                                                 argil::SurfaceToolProxy::Start::clear);
      REQUIRE(again.status.ok());
      CHECK(std::abs(again.X_WT.p.z() - m.X_WT.p.z()) <= 0.5 * kEps);
      CHECK_FALSE(f.proxy.crossing(floor, again.X_WT).crosses);
      check_contacts_at_end(f.proxy, floor, again);

      // Given the contacts where it starts, a move blocked there keeps them
      // (a marked copy comes back) and ends where it did without them; a
      // move that leaves its start queries where it ends.
      argil::ToolContacts marked = m.contacts;
      marked.per_surface[0].push_back(argil::Contact{.depth = 42.0});
      const argil::ToolMove kept = f.proxy.move(floor, m.X_WT, argil::Pose::at({x, 40.0, -2.0}),
                                                argil::SurfaceToolProxy::Start::clear, &marked);
      REQUIRE(kept.status.ok());
      CHECK(kept.X_WT.p == again.X_WT.p);
      if (again.X_WT.p == m.X_WT.p) {
        REQUIRE(kept.contacts.per_surface[0].size() == marked.per_surface[0].size());
        CHECK(kept.contacts.per_surface[0].back().depth == 42.0);
      } else {
        check_contacts_at_end(f.proxy, floor, kept);
      }
      const argil::ToolMove lifted = f.proxy.move(floor, m.X_WT, argil::Pose::at({x, 40.0, 3.0}),
                                                  argil::SurfaceToolProxy::Start::clear, &marked);
      REQUIRE(lifted.status.ok());
      CHECK(lifted.X_WT.p.z() == Approx(3.0).margin(1e-12));
      check_contacts_at_end(f.proxy, floor, lifted);
    }
  }
}

TEST_CASE("a B-spline tool's move returns the contacts where it stopped, free or sliding",
          "[haptic]") {
  Fixture f;
  const std::vector<const argil::SurfaceHierarchy*> floor{&f.wavy};
  SECTION("a free move ends at its target with no contacts") {
    const argil::Pose to = argil::Pose::at({40.0, 40.0, 8.0});
    const argil::ToolMove m = f.proxy.move(floor, argil::Pose::at({20.0, 30.0, 10.0}), to);
    REQUIRE(m.status.ok());
    CHECK((m.X_WT.p - to.p).norm() <= 1e-12);
    CHECK(m.contacts.per_surface[0].empty());
    CHECK_FALSE(m.contacts.crosses);
  }
  SECTION("moves into the wavy floor at a slant stop and slide without crossing") {
    for (int k = 0; k < 12; ++k) {
      const double x = 15.0 + 5.0 * k, y = 20.0 + 3.0 * k;
      const argil::ToolMove m = f.proxy.move(floor, argil::Pose::at({x, y, 6.0}),
                                             argil::Pose::at({x + 4.0, y - 2.0, -2.0}));
      REQUIRE(m.status.ok());
      // (A slide along the tangent plane may leave a bump: no contact then.)
      CHECK_FALSE(f.proxy.crossing(floor, m.X_WT).crosses);
      check_contacts_at_end(f.proxy, floor, m);
    }
  }
  SECTION("on a flat floor a slanted move slides to the target's foot, touching") {
    const std::vector<const argil::SurfaceHierarchy*> flat{&f.flat};
    for (int k = 0; k < 6; ++k) {
      const double x = 20.0 + 6.0 * k, y = 30.0 + 2.0 * k;
      const argil::ToolMove m = f.proxy.move(flat, argil::Pose::at({x, y, 6.0}),
                                             argil::Pose::at({x + 4.0, y - 2.0, -2.0}));
      REQUIRE(m.status.ok());
      CHECK_FALSE(f.proxy.crossing(flat, m.X_WT).crosses);
      CHECK(std::abs(m.X_WT.p.x() - (x + 4.0)) <= 1e-9);
      CHECK(std::abs(m.X_WT.p.y() - (y - 2.0)) <= 1e-9);
      argil::Pose lower = m.X_WT;
      lower.p.z() -= 0.5 * kEps + 1e-9;
      CHECK(f.proxy.crossing(flat, lower).crosses);
      CHECK_FALSE(m.contacts.per_surface[0].empty());
      check_contacts_at_end(f.proxy, flat, m);
    }
  }
}

TEST_CASE("a B-spline tool stops at a crossing in the middle of a move", "[haptic]") {
  // 5 mm above to 9 mm below: four substeps of 3.5 mm; the cap first crosses
  // the floor at the second (z = -2) and stops on it, far from the move's end.
  Fixture f;
  const std::vector<const argil::SurfaceHierarchy*> floor{&f.flat};
  const argil::ToolMove m =
      f.proxy.move(floor, argil::Pose::at({30.0, 40.0, 5.0}), argil::Pose::at({30.0, 40.0, -9.0}));
  REQUIRE(m.status.ok());
  CHECK_FALSE(f.proxy.crossing(floor, m.X_WT).crosses);
  argil::Pose lower = m.X_WT;
  lower.p.z() -= 0.5 * kEps + 1e-9;
  CHECK(f.proxy.crossing(floor, lower).crosses);
  CHECK(m.X_WT.p.z() > -2.0);
  check_contacts_at_end(f.proxy, floor, m);
}

TEST_CASE("a B-spline tool's move stops with the status of a failed query", "[haptic]") {
  // A surface 0.003 mm wide is too small for eps = 0.05 mm: its query fails.
  Fixture f;
  const argil::SurfaceHierarchy tiny =
      argil::SurfaceHierarchy::build(wavy_sheet(4, 0.001, 0.0), f.cache).value();
  const std::vector<const argil::SurfaceHierarchy*> surfaces{&f.flat, &tiny};
  const argil::ToolMove m = f.proxy.move(surfaces, argil::Pose::at({30.0, 40.0, 5.0}),
                                         argil::Pose::at({30.0, 40.0, -2.0}));
  CHECK(m.status.code == argil::StatusCode::invalid_argument);
  CHECK(m.status.message.find("tolerance") != std::string::npos);
}

TEST_CASE("a B-spline tool moved through a surface in one substep stops on it", "[haptic]") {
  // Substeps are up to max(size / 4, 10 eps) long: the cap, 2.4 mm tall,
  // moved 14 mm down in substeps of 2.9 mm lies wholly under the floor at the
  // last, and the flat sheet (no thickness) is clear at every end. The swept
  // test finds the crossing on the way, and both stop on the floor.
  Fixture f;
  argil::BSplineSurface sheet = wavy_sheet(4, 2.0, 0.0);
  sheet.control_points.col(0).array() -= 3.0;
  sheet.control_points.col(1).array() -= 3.0;
  argil::SurfaceToolProxy flat_tool =
      argil::SurfaceToolProxy::create(sheet, kEps, f.cache, kMaxContacts).value();
  const std::vector<const argil::SurfaceHierarchy*> floor{&f.flat};
  // Straight, and turning by 0.3 rad about a tilted axis on the way.
  const Eigen::Quaterniond turned(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 0).normalized()));
  for (argil::SurfaceToolProxy* proxy : {&f.proxy, &flat_tool}) {
    for (const Eigen::Quaterniond& R_to : {Eigen::Quaterniond::Identity(), turned}) {
      const argil::Pose from = argil::Pose::at({20.0, 30.0, 6.0});
      const argil::Pose to{R_to, {24.0, 28.0, -8.0}};
      CHECK_FALSE(proxy->crossing(floor, to).crosses);  // wholly under the floor
      const argil::ToolMove m = proxy->move(floor, from, to);
      REQUIRE(m.status.ok());
      CHECK_FALSE(proxy->crossing(floor, m.X_WT).crosses);
      // On the floor: its lowest point within eps of it.
      CHECK_FALSE(m.contacts.per_surface[0].empty());
      for (const argil::Contact& c : m.contacts.per_surface[0]) CHECK(c.depth >= -kEps);
      // On top: the control points' centre above the floor.
      const argil::BSplineSurface& shape = proxy == &flat_tool ? sheet : bowl_cap();
      const Eigen::Vector3d centre = shape.control_points.colwise().mean().transpose();
      CHECK(argil::apply(m.X_WT, centre).z() > 0.0);
    }
  }
}

TEST_CASE("a B-spline tool turned in place on a floor stops before its rim dips in", "[haptic]") {
  // No translation: the stop search has no way to step along, and must stop
  // where the turn starts rather than where it crosses.
  Fixture f;
  const std::vector<const argil::SurfaceHierarchy*> floor{&f.flat};
  const argil::ToolMove rest =
      f.proxy.move(floor, argil::Pose::at({40.0, 40.0, 5.0}), argil::Pose::at({40.0, 40.0, -2.0}));
  REQUIRE(rest.status.ok());
  REQUIRE_FALSE(rest.contacts.per_surface[0].empty());
  for (const double angle : {0.15, 0.3}) {
    CAPTURE(angle);
    const argil::Pose turned{Eigen::Quaterniond(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitX())),
                             rest.X_WT.p};
    REQUIRE(f.proxy.crossing(floor, turned).crosses);  // the rim dips into the floor
    const argil::ToolMove m =
        f.proxy.move(floor, rest.X_WT, turned, argil::SurfaceToolProxy::Start::clear);
    REQUIRE(m.status.ok());
    CHECK_FALSE(f.proxy.crossing(floor, m.X_WT).crosses);
    check_contacts_at_end(f.proxy, floor, m);
  }
}
