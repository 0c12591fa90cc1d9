// Joined faces (docs/deformation.md, Joined faces): two panels that share an
// edge, pressed across it, stay together along it (G0 within eps) and, where
// they met flat, tangent (G1); unjoined they come apart. The gap and the angle
// are measured here on the surfaces, not by the joint.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <tuple>
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

/// A world for the 2 mm sphere at eps 0.01 mm, coupled by 1 N/mm.
argil::HapticWorld sphere_world() {
  argil::WorldOptions o;
  o.tolerance = kEps;
  o.coupling = {.stiffness = 1.0, .damping = 0.0, .max_force = 100.0};
  auto created = argil::HapticWorld::create(argil::SphereToolShape{kRadius}, o);
  REQUIRE(created.ok());
  return std::move(created).value();
}

/// Clay panel a over [0, 10] x [0, 10], held along x = 0, and panel b beside
/// it along x = 10 (turned by `fold`), held along its far edge: bodies 0, 1.
void add_panels(argil::HapticWorld& w, double fold) {
  const argil::Material clay = *argil::material_preset("clay");
  argil::BoundaryConditions held_u0, held_u1;
  held_u0.fixed_u0 = true;
  held_u1.fixed_u1 = true;
  REQUIRE(w.add_deformable(panel_at({0, 0, 0}), clay, held_u0, 0.3).ok());
  REQUIRE(w.add_deformable(panel_at({kSize, 0, 0}, fold), clay, held_u1, 0.3).ok());
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
  argil::HapticWorld w = sphere_world();
  add_panels(w, fold);
  const argil::BSplineSurface b = panel_at({kSize, 0, 0}, fold);
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
  argil::HapticWorld w = sphere_world();
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

namespace {

/// A flat 20 x 10 mm bicubic panel: 10 spans along x (u), 5 along y (v).
argil::BSplineSurface long_panel() {
  argil::BSplineSurface s;
  s.degree = {3, 3};
  s.knots = {argil::test::piece_knots(3, 10, 1), argil::test::piece_knots(3, 5, 1)};
  const Eigen::VectorXd gu = argil::greville_abscissae(3, s.knots[0]);
  const Eigen::VectorXd gv = argil::greville_abscissae(3, s.knots[1]);
  s.control_points.resize(gu.size() * gv.size(), 3);
  for (Eigen::Index i = 0; i < gu.size(); ++i)
    for (Eigen::Index j = 0; j < gv.size(); ++j)
      s.control_points.row(s.pole_index(static_cast<int>(i), static_cast<int>(j)))
          << 2 * kSize * gu[i],
          kSize * gv[j], 0.0;
  return s;
}

/// `whole`'s part over u in [u0, u1], where both are knots of full
/// multiplicity (degree): the same surface, with the same parameters.
argil::BSplineSurface u_piece(const argil::BSplineSurface& whole, double u0, double u1) {
  const int p = whole.degree[0], nv = whole.count(argil::Direction::v);
  const Eigen::VectorXd& k = whole.knots[0];
  // Clamped at both ends: u0 and u1 each p + 1 times.
  std::vector<double> knots(static_cast<std::size_t>(p + 1), u0);
  for (Eigen::Index i = 0; i < k.size(); ++i)
    if (k[i] > u0 && k[i] < u1) knots.push_back(k[i]);
  knots.insert(knots.end(), static_cast<std::size_t>(p + 1), u1);
  // The first pole: at u0 the surface passes through the pole before u0's
  // first copy (the net's first pole at its start).
  Eigen::Index first = 0;
  while (k[first] < u0) ++first;
  if (first > 0) first -= 1;
  argil::BSplineSurface s;
  s.degree = whole.degree;
  s.knots[0] =
      Eigen::Map<const Eigen::VectorXd>(knots.data(), static_cast<Eigen::Index>(knots.size()));
  s.knots[1] = whole.knots[1];
  const int nu = static_cast<int>(knots.size()) - p - 1;
  s.control_points.resize(static_cast<Eigen::Index>(nu) * nv, 3);
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j)
      s.control_points.row(s.pole_index(i, j)) =
          whole.control_points.row(whole.pole_index(static_cast<int>(first) + i, j));
  return s;
}

struct SplitOutcome {
  double peak_force = 0.0;             // [N]
  double dent = 0.0;                   // deepest pole below the rest plane [mm]
  std::vector<Eigen::Vector3d> shape;  // the surface on a grid of (u, v), after settling
};

enum class Cut { none, joined, loose };

/// The panel held along x = 0 and x = 20, as one face or as two faces along
/// x = 10 (joined or not); the device taken 2 mm down 1 mm beside that line,
/// held, released, and the panel left to settle.
SplitOutcome press_panel(Cut cut_at_middle) {
  const bool split = cut_at_middle != Cut::none;
  argil::HapticWorld w = sphere_world();
  const argil::Material clay = *argil::material_preset("clay");
  argil::BoundaryConditions held_u0, held_u1, held_both;
  held_u0.fixed_u0 = true;
  held_u1.fixed_u1 = true;
  held_both.fixed_u0 = held_both.fixed_u1 = true;
  const argil::BSplineSurface whole = long_panel();
  if (split) {
    const argil::Result<argil::BSplineSurface> cut =
        argil::insert_knot(whole, argil::Direction::u, 0.5, 2);
    REQUIRE(cut.ok());
    for (const auto& [from, to, held] :
         {std::tuple{0.0, 0.5, held_u0}, std::tuple{0.5, 1.0, held_u1}}) {
      const argil::Result<int> added =
          w.add_deformable(u_piece(cut.value(), from, to), clay, held, 0.3);
      INFO(added.status().message);
      REQUIRE(added.ok());
    }
    if (cut_at_middle == Cut::joined)
      REQUIRE(w.join(0, uv_line({0.5, 0}, {0.5, 1}), 1, uv_line({0.5, 0}, {0.5, 1})).ok());
  } else {
    REQUIRE(w.add_deformable(whole, clay, held_both, 0.3).ok());
  }
  const auto shape = [&] {
    std::vector<Eigen::Vector3d> points;
    for (int a = 0; a <= 40; ++a) {
      for (int c = 0; c <= 20; ++c) {
        const double u = a / 40.0, v = c / 20.0;
        points.push_back(argil::evaluate(w.surface(split && u > 0.5 ? 1 : 0), u, v));
      }
    }
    return points;
  };
  // The pieces are the uncut panel, parameters and all.
  const std::vector<Eigen::Vector3d> at_rest = shape();
  for (std::size_t k = 0; k < at_rest.size(); ++k) {
    const double u = static_cast<double>(k / 21) / 40.0, v = static_cast<double>(k % 21) / 20.0;
    REQUIRE((at_rest[k] - argil::evaluate(whole, u, v)).norm() <= 1e-12);
  }
  SplitOutcome out;
  const Eigen::Vector3d top(kSize - 1.0, 0.5 * kSize, kRadius + 0.5);
  for (int t = 0; t < 2500; ++t) {
    const double depth = t < 500 ? 2.0 * t / 500.0 : t < 800 ? 2.0 : 0.0;
    const argil::DeviceSample s{.tick = t,
                                .t = t * kDt,
                                .X_WD = argil::Pose::at(top - Eigen::Vector3d(0, 0, depth)),
                                .engaged = t < 800};
    const argil::TickResult r = w.step(s, kDt);
    INFO(r.status.message);
    REQUIRE(r.status.ok());
    out.peak_force = std::max(out.peak_force, r.force.norm());
  }
  for (int b = 0; b < w.body_count(); ++b)
    out.dent = std::max(out.dent, -w.surface(b).control_points.col(2).minCoeff());
  out.shape = shape();
  return out;
}

double largest_distance(const std::vector<Eigen::Vector3d>& a,
                        const std::vector<Eigen::Vector3d>& b) {
  double out = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) out = std::max(out, (a[k] - b[k]).norm());
  return out;
}

}  // namespace

TEST_CASE("joints: a panel cut in two and joined deforms as the uncut panel", "[haptic][joint]") {
  const SplitOutcome whole = press_panel(Cut::none);
  const SplitOutcome joined = press_panel(Cut::joined);
  const SplitOutcome loose = press_panel(Cut::loose);
  const double joined_apart = largest_distance(whole.shape, joined.shape);
  const double loose_apart = largest_distance(whole.shape, loose.shape);
  CAPTURE(whole.peak_force, joined.peak_force, whole.dent, joined.dent, joined_apart, loose_apart);
  REQUIRE(whole.dent > 0.5);
  // Unjoined, the cut opens: the check below can fail.
  REQUIRE(loose_apart > 0.3 * whole.dent);
  // The joint keeps position and tangent plane along the cut, not curvature
  // (the uncut panel is C2 there): the joined pair bends a little more at
  // the cut, by some 10 % of the dent beside it.
  CHECK(joined_apart <= 0.15 * whole.dent);
  CHECK(std::abs(joined.dent - whole.dent) <= 0.03 * whole.dent);
  CHECK(std::abs(joined.peak_force - whole.peak_force) <= 0.02 * whole.peak_force);
}

namespace {

/// Panels a and b of press_across, flat and joined, in a fresh world.
argil::HapticWorld joined_panels() {
  argil::HapticWorld w = sphere_world();
  add_panels(w, 0.0);
  REQUIRE(w.join(0, uv_line({1, 0}, {1, 1}), 1, uv_line({0, 0}, {0, 1})).ok());
  return w;
}

/// Brings the tool straight down from `start` at 0.01 mm a tick until it
/// touches; whether joint 0 was prepared before that tick.
bool ready_before_contact(argil::HapticWorld& w, const Eigen::Vector3d& start) {
  bool ready = false;
  int first_contact = -1;
  for (int t = 0; t < 800 && first_contact < 0; ++t) {
    const argil::DeviceSample s{.tick = t,
                                .t = t * kDt,
                                .X_WD = argil::Pose::at(start - Eigen::Vector3d(0, 0, 0.01 * t)),
                                .engaged = true};
    ready = w.joint(0).joint.ready();
    const argil::TickResult r = w.step(s, kDt);
    REQUIRE(r.status.ok());
    if (r.contacts > 0) first_contact = t;
  }
  REQUIRE(first_contact > 0);
  return ready;
}

}  // namespace

TEST_CASE("joints: an edge the tool comes near is prepared before the contact tick",
          "[haptic][joint]") {
  argil::HapticWorld w = joined_panels();
  REQUIRE_FALSE(w.joint(0).joint.ready());
  // From 6 mm above the edge down into it at 0.01 mm a tick.
  const Eigen::Vector3d start(kSize - 0.5, 0.5 * kSize, kRadius + 6.0);
  CHECK(ready_before_contact(w, start));
}

TEST_CASE(
    "joints: an edge beyond the tool's reach but within the clay's spread is prepared before "
    "contact",
    "[haptic][joint]") {
  argil::HapticWorld w = joined_panels();
  REQUIRE_FALSE(w.joint(0).joint.ready());
  // Down onto panel a halfway between one tool reach (2 r + 4 eps) and that
  // plus the clay's influence length from the edge: a dent there reaches it.
  const double reach = 2.0 * kRadius + 4.0 * kEps;
  const double spread = w.deformable(0)->influence_length();
  REQUIRE(reach + spread < kSize);
  const Eigen::Vector3d start(kSize - reach - 0.5 * spread, 0.5 * kSize, kRadius + 3.0);
  CHECK(ready_before_contact(w, start));
}

TEST_CASE("joints: an edge the tool stays away from is not prepared", "[haptic][joint]") {
  argil::HapticWorld w = joined_panels();
  // Over panel a, 0.5 mm above it, along y, farther from the edge at x = 10
  // than one tool reach and the clay's influence length.
  const double away = 2.0 * kRadius + 4.0 * kEps + w.deformable(0)->influence_length() + 0.2;
  REQUIRE(away < kSize);
  for (int t = 0; t < 500; ++t) {
    const Eigen::Vector3d p(kSize - away, 1.0 + 0.016 * t, kRadius + 0.5);
    const argil::DeviceSample s{
        .tick = t, .t = t * kDt, .X_WD = argil::Pose::at(p), .engaged = true};
    const argil::TickResult r = w.step(s, kDt);
    REQUIRE(r.status.ok());
    REQUIRE(r.contacts == 0);
  }
  CHECK_FALSE(w.joint(0).joint.ready());
}

TEST_CASE("joints: no edge is prepared ahead in a tick with contact", "[haptic][joint]") {
  // The panels under a rigid plate 1 mm above them: the tool slides over the
  // plate, in contact every tick, from beyond the edge's reach to right over
  // it, and never touches the panels. Their joint never opens, so only the
  // preparation ahead could prepare it, and it must wait for a tick without
  // contact.
  argil::HapticWorld w = joined_panels();
  constexpr double kPlate = 1.0;
  argil::BSplineSurface plate = argil::test::flat_bicubic_panel(60.0, 5);
  plate.control_points.rowwise() += Eigen::RowVector3d(-40.0, -25.0, kPlate);
  REQUIRE(w.add_rigid(plate, 0.0).ok());
  const double ahead = 2.0 * kRadius + 4.0 * kEps + w.deformable(0)->influence_length();
  REQUIRE(kPlate + kRadius < ahead);  // over the edge, the tool is within its reach

  // Down onto the plate beyond the edge's reach, then along x over the edge,
  // pressed 0.2 mm into the plate; then up off it, still within reach.
  const double x0 = kSize - ahead - 5.0;
  const double press_z = kPlate + kRadius - 0.2;
  int t = 0;
  const auto step = [&](const Eigen::Vector3d& device) {
    const argil::DeviceSample s{
        .tick = t, .t = t * kDt, .X_WD = argil::Pose::at(device), .engaged = true};
    ++t;
    const argil::TickResult r = w.step(s, kDt);
    REQUIRE(r.status.ok());
    return r;
  };
  for (int k = 0; k <= 100; ++k) {
    (void)step({x0, 0.5 * kSize, press_z + 0.01 * (100 - k)});
    REQUIRE_FALSE(w.joint(0).joint.ready());
  }
  for (int k = 0; k <= 1000; ++k) {
    const double x = x0 + (kSize - x0) * k / 1000.0;
    const argil::TickResult r = step({x, 0.5 * kSize, press_z});
    REQUIRE(r.contacts > 0);
    REQUIRE(r.body_contacts[0].empty());
    REQUIRE(r.body_contacts[1].empty());
    REQUIRE_FALSE(w.joint(0).joint.ready());
  }
  REQUIRE((step({kSize, 0.5 * kSize, press_z}).proxy.X_WT.p -
           Eigen::Vector3d(kSize, 0.5 * kSize, kPlate + kRadius))
              .norm() < 0.1);
  // Lifted off, a tick without contact prepares it.
  bool ready = false;
  for (int k = 0; k < 50 && !ready; ++k) {
    const argil::TickResult r = step({kSize, 0.5 * kSize, kPlate + kRadius + 0.5});
    ready = r.contacts == 0 && w.joint(0).joint.ready();
  }
  CHECK(ready);
}
