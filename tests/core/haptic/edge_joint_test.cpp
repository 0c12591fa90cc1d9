// Joined faces (docs/deformation.md, Joined faces): two panels that share an
// edge, pressed across it, stay together along it (G0 within eps) and, where
// they met flat, tangent (G1); unjoined they come apart. The gap and the angle
// are measured here on the surfaces, not by the joint.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <vector>

#include "argil/core.hpp"
#include "support/test_plates.hpp"

namespace {

constexpr double kEps = 0.01;
constexpr double kRadius = 2.0;
constexpr double kDt = 1e-3;
constexpr double kSize = 10.0;

/// A flat 10 x 10 mm bicubic panel with 8 x 8 poles, its corner at `corner`,
/// turned about its u = 0 edge by `fold` [rad] (0: flat).
argil::BSplineSurface panel_at(const Eigen::Vector3d& corner, double fold = 0.0) {
  argil::BSplineSurface s = argil::test::flat_bicubic_panel(kSize, 5);
  for (Eigen::Index k = 0; k < s.control_points.rows(); ++k) {
    const double x = s.control_points(k, 0);
    s.control_points(k, 0) = x * std::cos(fold);
    s.control_points(k, 2) = x * std::sin(fold);
  }
  s.control_points.rowwise() += corner.transpose();
  return s;
}

/// The line from `from` to `to` in a face's (u, v).
argil::BSplineCurve uv_line(const Eigen::Vector2d& from, const Eigen::Vector2d& to) {
  argil::BSplineCurve c;
  c.degree = 1;
  c.knots = Eigen::Vector4d(0, 0, 1, 1);
  c.points.resize(2, 2);
  c.points.row(0) = from.transpose();
  c.points.row(1) = to.transpose();
  return c;
}

struct Outcome {
  double gap = 0.0;      // largest distance between the faces along the edge [mm]
  double angle = 0.0;    // largest angle between their normals along it [rad]
  double dent = 0.0;     // deepest point of a, below its rest plane [mm]
  double carried = 0.0;  // deepest point of b [mm]
  int tangent_samples = 0;
};

/// Panel a over [0, 10] x [0, 10] and panel b beside it along x = 10 (turned
/// by `fold`), held along their far edges; a sphere pressed 1 mm down across
/// the shared edge, held, released, and left to settle.
Outcome press_across(bool joined, double fold) {
  argil::WorldOptions o;
  o.tolerance = kEps;
  o.coupling = {.stiffness = 1.0, .damping = 0.0, .max_force = 100.0};
  auto created = argil::HapticWorld::create(argil::SphereToolShape{kRadius}, o);
  REQUIRE(created.ok());
  argil::HapticWorld w = std::move(created).value();
  const argil::Material clay = *argil::material_preset("clay");
  argil::BoundaryConditions held_u0, held_u1;
  held_u0.fixed_u0 = true;
  held_u1.fixed_u1 = true;
  const argil::BSplineSurface a = panel_at({0, 0, 0});
  const argil::BSplineSurface b = panel_at({kSize, 0, 0}, fold);
  REQUIRE(w.add_deformable(a, clay, held_u0, 0.3).ok());
  REQUIRE(w.add_deformable(b, clay, held_u1, 0.3).ok());
  Outcome out;
  if (joined) {
    const argil::Result<int> j = w.join(0, uv_line({1, 0}, {1, 1}), 1, uv_line({0, 0}, {0, 1}));
    REQUIRE(j.ok());
    out.tangent_samples = w.joint(j.value()).joint.tangent_count();
  }
  const Eigen::Vector3d top(kSize - 0.5, 0.5 * kSize, kRadius + 0.5);
  for (int t = 0; t < 1500; ++t) {
    const double depth = t < 500 ? 1.5 * t / 500.0 : t < 800 ? 1.5 : 0.0;
    const argil::DeviceSample s{.tick = t,
                                .t = t * kDt,
                                .X_WD = argil::Pose::at(top - Eigen::Vector3d(0, 0, depth)),
                                .engaged = t < 800};
    const argil::TickResult r = w.step(s, kDt);
    INFO(r.status.message);
    REQUIRE(r.status.ok());
  }
  for (int k = 0; k <= 200; ++k) {
    const double v = k / 200.0;
    const Eigen::Vector3d pa = argil::evaluate(w.surface(0), 1.0, v);
    const Eigen::Vector3d pb = argil::evaluate(w.surface(1), 0.0, v);
    out.gap = std::max(out.gap, (pa - pb).norm());
    const Eigen::Vector3d na = argil::unit_normal(w.surface(0), 1.0, v);
    const Eigen::Vector3d nb = argil::unit_normal(w.surface(1), 0.0, v);
    const double rest = fold;
    out.angle = std::max(out.angle, std::abs(std::atan2(na.cross(nb).norm(), na.dot(nb)) - rest));
  }
  out.dent = -w.surface(0).control_points.col(2).minCoeff();
  const argil::ControlNet moved = w.surface(1).control_points - b.control_points;
  out.carried = moved.rowwise().norm().maxCoeff();
  return out;
}

}  // namespace

TEST_CASE("joints: flat panels pressed across their edge stay together and tangent",
          "[haptic][joint]") {
  const Outcome free = press_across(false, 0.0);
  const Outcome joined = press_across(true, 0.0);
  CAPTURE(free.gap, free.angle, free.dent, joined.gap, joined.angle, joined.dent, joined.carried);
  REQUIRE(joined.tangent_samples > 0);
  // Unjoined the press opens the edge: the check below can fail.
  REQUIRE(free.gap > 5 * kEps);
  REQUIRE(joined.dent > 0.2);
  REQUIRE(joined.gap <= kEps);
  REQUIRE(joined.angle <= argil::kTangentJoinAngle);
  // The neighbour is carried with the pressed face near the edge.
  REQUIRE(joined.carried > 0.5 * joined.dent);
}

TEST_CASE("joints: panels meeting at a crease stay together and keep its angle",
          "[haptic][joint]") {
  const double fold = 0.5;  // about 29 degrees: a crease, not G1
  const Outcome free = press_across(false, fold);
  const Outcome joined = press_across(true, fold);
  CAPTURE(free.gap, joined.gap, joined.angle, joined.dent, joined.carried);
  REQUIRE(joined.tangent_samples == 0);
  REQUIRE(free.gap > 5 * kEps);
  REQUIRE(joined.gap <= kEps);
  // The crease turns as one: its angle is kept, it is no hinge.
  REQUIRE(joined.angle <= argil::kTangentJoinAngle);
}

namespace {

/// A closed bicubic tube about the z axis, 10 mm across and 20 mm long, with
/// 14 x 6 poles: its u = 0 and u = 1 rows coincide (the seam), and the poles
/// either side of the seam are in line with it, so it is tangent-continuous there.
argil::BSplineSurface tube() {
  constexpr int nu = 14, nv = 6;
  constexpr double r = 5.0, length = 20.0;
  argil::BSplineSurface s;
  s.degree = {3, 3};
  s.knots[0] = argil::test::piece_knots(3, nu - 3, 1);
  s.knots[1] = argil::test::piece_knots(3, nv - 3, 1);
  s.control_points.resize(nu * nv, 3);
  const double step = 2.0 * std::numbers::pi / (nu - 2);
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      const double z = length * j / (nv - 1);
      Eigen::RowVector3d p;
      if (i == 0 || i == nu - 1) {
        p << r * std::cos(0.5 * step), 0.0, z;  // between its neighbours
      } else {
        const double phi = step * (i - 0.5);
        p << r * std::cos(phi), r * std::sin(phi), z;
      }
      s.control_points.row(s.pole_index(i, j)) = p;
    }
  }
  return s;
}

struct SeamOutcome {
  double gap = 0.0;     // largest distance between the seam's two sides [mm]
  double angle = 0.0;   // largest angle between their normals [rad]
  double dent = 0.0;    // how far the seam's middle went in [mm]
  bool exact = false;   // the seam's two rows of poles equal to the bit
  bool asleep = false;  // settled once the tool went away
};

/// The tube held at both ends, a sphere pressed 1.5 mm into it just beside
/// its seam, held, released, and left to settle with the tool taken away.
SeamOutcome press_beside_seam(bool joined) {
  argil::WorldOptions o;
  o.tolerance = kEps;
  o.coupling = {.stiffness = 1.0, .damping = 0.0, .max_force = 100.0};
  auto created = argil::HapticWorld::create(argil::SphereToolShape{kRadius}, o);
  REQUIRE(created.ok());
  argil::HapticWorld w = std::move(created).value();
  argil::BoundaryConditions ends;
  ends.fixed_v0 = true;
  ends.fixed_v1 = true;
  const argil::BSplineSurface rest = tube();
  REQUIRE(w.add_deformable(rest, *argil::material_preset("clay"), ends, 0.3).ok());
  if (joined) {
    const argil::Result<int> j = w.join(0, uv_line({0, 0}, {0, 1}), 0, uv_line({1, 0}, {1, 1}));
    REQUIRE(j.ok());
    REQUIRE(w.joint(j.value()).welded.size() == 6);
  }
  const double r0 = rest.control_points(0, 0);
  // Beside the seam (the tool's centre 0.6 mm off it), so the press is lopsided.
  const Eigen::Vector3d outside(r0 + kRadius + 0.5, 0.6, 10.0);
  for (int t = 0; t < 1500; ++t) {
    const double depth = t < 500 ? 1.5 * t / 500.0 : t < 800 ? 1.5 : 0.0;
    const argil::DeviceSample s{.tick = t,
                                .t = t * kDt,
                                .X_WD = argil::Pose::at(outside - Eigen::Vector3d(depth, 0, 0)),
                                .engaged = t < 800};
    const argil::TickResult r = w.step(s, kDt);
    INFO(r.status.message);
    REQUIRE(r.status.ok());
  }
  // The tool taken away: the tube settles and sleeps, welded seam and all.
  for (int t = 1500; t < 4000; ++t) {
    const argil::DeviceSample s{.tick = t,
                                .t = t * kDt,
                                .X_WD = argil::Pose::at(outside + Eigen::Vector3d(30, 0, 0)),
                                .engaged = false};
    const argil::TickResult r = w.step(s, kDt);
    INFO(r.status.message);
    REQUIRE(r.status.ok());
  }
  SeamOutcome out;
  out.asleep = w.asleep(0);
  const argil::BSplineSurface& s = w.surface(0);
  for (int k = 0; k <= 200; ++k) {
    const double v = k / 200.0;
    out.gap = std::max(out.gap, (argil::evaluate(s, 0.0, v) - argil::evaluate(s, 1.0, v)).norm());
    const Eigen::Vector3d n0 = argil::unit_normal(s, 0.0, v), n1 = argil::unit_normal(s, 1.0, v);
    out.angle = std::max(out.angle, std::atan2(n0.cross(n1).norm(), n0.dot(n1)));
  }
  out.dent = r0 - argil::evaluate(s, 0.0, 0.5).x();
  out.exact = true;
  for (int j = 0; j < s.count(argil::Direction::v); ++j) {
    const Eigen::RowVector3d a = s.control_points.row(s.pole_index(0, j));
    const Eigen::RowVector3d b =
        s.control_points.row(s.pole_index(s.count(argil::Direction::u) - 1, j));
    out.exact = out.exact && a == b;
  }
  return out;
}

}  // namespace

TEST_CASE("joints: a closed tube pressed beside its seam stays closed and tangent there",
          "[haptic][joint]") {
  const SeamOutcome free = press_beside_seam(false);
  const SeamOutcome joined = press_beside_seam(true);
  CAPTURE(free.gap, free.angle, free.dent, joined.gap, joined.angle, joined.dent);
  // Unjoined the press opens the seam: the checks below can fail.
  REQUIRE(free.gap > 5 * kEps);
  REQUIRE(joined.dent > 0.2);
  REQUIRE(joined.exact);
  REQUIRE(joined.asleep);
  REQUIRE(joined.gap == 0.0);
  REQUIRE(joined.angle <= argil::kTangentJoinAngle);
}

TEST_CASE("joints: bad joins are refused", "[haptic][joint]") {
  argil::WorldOptions o;
  o.tolerance = kEps;
  auto created = argil::HapticWorld::create(argil::SphereToolShape{kRadius}, o);
  REQUIRE(created.ok());
  argil::HapticWorld w = std::move(created).value();
  REQUIRE(w.add_rigid(panel_at({0, 0, 0}), 0.3).ok());
  REQUIRE(w.add_rigid(panel_at({kSize, 0, 0}), 0.3).ok());
  const argil::BSplineCurve edge = uv_line({1, 0}, {1, 1});
  CHECK_FALSE(w.join(0, edge, 1, edge).ok());  // both rigid
  CHECK_FALSE(w.join(0, edge, 5, edge).ok());  // no body 5
  argil::BSplineCurve bad = edge;
  bad.knots[2] = -1.0;
  REQUIRE(w.add_deformable(panel_at({0, kSize, 0}), argil::Material{}, {}, 0.3).ok());
  const argil::Result<int> r = w.join(2, bad, 0, edge);
  REQUIRE_FALSE(r.ok());
  CHECK(r.status().message.find("edge curve") != std::string::npos);
  CHECK(w.joint_count() == 0);
}
