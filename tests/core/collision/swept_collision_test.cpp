// The swept surface-surface query (collide_swept): a surface moved through
// another in one query crosses it though neither end does; checked against a
// dense sampling of the motion with the static query (itself checked against
// OpenCASCADE elsewhere).
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>

#include "argil/core.hpp"
#include "support/tool_shapes.hpp"
#include "surface_pairs.hpp"

using argil::BSplineSurface;
using argil::CollisionRequest;
using argil::Pose;

namespace {

CollisionRequest crossing_test(double eps) {
  return {.tolerance = eps,
          .max_contacts = 1,
          .refine = false,
          .compute_depth = false,
          .first_crossing_only = true,
          .curves = false};
}

/// The first crossing (a contact of depth 0 or more); null when none.
const argil::Contact* first_crossing(const argil::CollisionResult& r) {
  REQUIRE(r.status.ok());
  for (const argil::Contact& c : r.contacts)
    if (c.depth >= 0.0) return &c;
  return nullptr;
}

bool crosses(const argil::CollisionResult& r) { return first_crossing(r) != nullptr; }

/// A flat 4 x 4 bicubic sheet `width` mm wide in z = 0, centred on its origin:
/// no thickness at all.
BSplineSurface flat_tool(double width) {
  BSplineSurface s = argil::test::wavy_sheet(4, width / 3.0, 0.0);
  s.control_points.col(0).array() -= 0.5 * width;
  s.control_points.col(1).array() -= 0.5 * width;
  return s;
}

}  // namespace

TEST_CASE("a sheet swept through a floor in one query crosses it, though neither end does",
          "[collision][swept]") {
  const double eps = 0.05;
  // A 6 mm sheet through a 90 mm floor (its corners pass through the floor)
  // and a 60 mm sheet through a 5 mm floor (the floor's corners pass through
  // it), each clear of the other's leaf corners and edges.
  BSplineSurface small_floor = argil::test::wavy_sheet(4, 5.0 / 3.0, 0.0);
  small_floor.control_points.col(0).array() += 50.0;
  small_floor.control_points.col(1).array() += 40.0;
  const argil::SurfaceHierarchy floors[] = {
      argil::test::hierarchy_for(argil::test::wavy_sheet(10, 10.0, 0.0)),
      argil::test::hierarchy_for(small_floor)};
  const argil::SurfaceHierarchy tools[] = {argil::test::hierarchy_for(flat_tool(6.0)),
                                           argil::test::hierarchy_for(flat_tool(60.0))};
  // Level, tilted 0.3 rad, and turning by 0.1 rad on the way down.
  const Eigen::Quaterniond tilt(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()));
  const Eigen::Quaterniond turn(Eigen::AngleAxisd(0.1, Eigen::Vector3d(1, 1, 0).normalized()));
  for (int pair = 0; pair < 2; ++pair) {
    for (const auto& [R_from, R_to] :
         {std::pair{Eigen::Quaterniond::Identity(), Eigen::Quaterniond::Identity()},
          std::pair{tilt, tilt}, std::pair{tilt, Eigen::Quaterniond(turn * tilt)}}) {
      CAPTURE(pair, R_from.coeffs().transpose(), R_to.coeffs().transpose());
      const argil::SurfaceHierarchy& floor = floors[pair];
      const argil::SurfaceHierarchy& tool = tools[pair];
      const Pose from{R_from, {44.0, 45.0, 3.0}}, to{R_to, {46.0, 44.0, -3.0}};
      CHECK_FALSE(crosses(argil::collide(floor, tool, from, crossing_test(eps))));
      CHECK_FALSE(crosses(argil::collide(floor, tool, to, crossing_test(eps))));
      const argil::CollisionResult swept =
          argil::collide_swept(floor, tool, from, to, crossing_test(eps));
      REQUIRE(crosses(swept));
      // The crossing is reported on the floor, where the tool went through.
      const argil::Contact& c = swept.contacts.front();
      CHECK(std::abs(c.point.z()) <= 1e-9);
      const Eigen::Vector2d where =
          pair == 0 ? Eigen::Vector2d(45.0, 44.5) : Eigen::Vector2d(52.5, 42.5);
      CHECK((c.point.head<2>() - where).norm() < 4.5);
    }
  }
}

TEST_CASE("a sheet moved through a floor by less than eps crosses it", "[collision][swept]") {
  // Within eps the pairs that can meet on the way are those the end's own
  // descent reaches: no descent over the motion runs.
  const double eps = 0.05;
  const argil::SurfaceHierarchy floor =
      argil::test::hierarchy_for(argil::test::wavy_sheet(10, 10.0, 0.0));
  const argil::SurfaceHierarchy tool = argil::test::hierarchy_for(flat_tool(6.0));
  for (const double drop : {0.04, 0.5 * eps, eps}) {
    CAPTURE(drop);
    const Pose from = Pose::at({44.0, 45.0, 0.5 * drop}), to = Pose::at({44.0, 45.0, -0.5 * drop});
    CHECK_FALSE(crosses(argil::collide(floor, tool, from, crossing_test(eps))));
    CHECK_FALSE(crosses(argil::collide(floor, tool, to, crossing_test(eps))));
    CHECK(crosses(argil::collide_swept(floor, tool, from, to, crossing_test(eps))));
    // The contact query reports it too, and not when the sheet stops short.
    const CollisionRequest contacts{
        .tolerance = eps, .refine = false, .compute_depth = false, .curves = false};
    CHECK(crosses(argil::collide_swept(floor, tool, from, to, contacts)));
    CHECK_FALSE(crosses(
        argil::collide_swept(floor, tool, from, Pose::at({44.0, 45.0, 0.1 * drop}), contacts)));
  }
}

TEST_CASE("a sheet swept along a floor without reaching it does not cross it",
          "[collision][swept]") {
  const double eps = 0.05;
  const argil::SurfaceHierarchy floor =
      argil::test::hierarchy_for(argil::test::wavy_sheet(10, 10.0, 0.0));
  const argil::SurfaceHierarchy tool = argil::test::hierarchy_for(flat_tool(6.0));
  for (const double height : {0.5 * eps, 2.0 * eps, 1.0}) {
    CAPTURE(height);
    const Pose from = Pose::at({20.0, 20.0, height}), to = Pose::at({60.0, 35.0, height});
    const argil::CollisionResult swept =
        argil::collide_swept(floor, tool, from, to, crossing_test(eps));
    CHECK_FALSE(crosses(swept));
    // Touching within eps at the end is a contact, not a crossing.
    const argil::CollisionResult touch = argil::collide_swept(
        floor, tool, from, to,
        {.tolerance = eps, .refine = false, .compute_depth = false, .curves = false});
    CHECK_FALSE(crosses(touch));
    CHECK(touch.contacts.empty() == (height > eps));
    // Nothing met on the way: the very contacts of the query at the end.
    const argil::CollisionResult at_end = argil::collide(
        floor, tool, to,
        {.tolerance = eps, .refine = false, .compute_depth = false, .curves = false});
    CHECK(argil::test::same_contacts(touch, at_end));
  }
}

namespace {

/// A random graph patch 10 mm wide (degree up to 3) centred on its origin.
BSplineSurface centred_patch(std::mt19937_64& rng, double amplitude) {
  BSplineSurface patch = argil::test::graph_surface(rng, 10.0, amplitude, 0.0, 3, 2);
  patch.control_points.col(0).array() -= 5.0;
  patch.control_points.col(1).array() -= 5.0;
  return patch;
}

/// What the random swept cases exercised.
struct SweptTally {
  int clear_runs = 0, swept_crossings = 0, passed_through = 0;
};

/// Checks the swept query of b (a copy of `patch`) from `from` to `to` against
/// samples of the motion eps / 4 apart: every crossing the samples find is
/// found, every reported one has a sampled pose within 3 eps, and b's point at
/// its uv_b passes within eps of it. Motions whose start crosses are skipped.
void check_against_sampling(const argil::SurfaceHierarchy& a, const argil::SurfaceHierarchy& b,
                            const BSplineSurface& patch, const Pose& from, const Pose& to,
                            double eps, SweptTally& tally) {
  if (crosses(argil::collide(a, b, from, crossing_test(eps)))) return;
  ++tally.clear_runs;
  const argil::CollisionResult swept_result =
      argil::collide_swept(a, b, from, to, crossing_test(eps));
  const argil::Contact* crossing = first_crossing(swept_result);
  const bool swept = crossing != nullptr;
  tally.swept_crossings += swept ? 1 : 0;
  const bool end_crosses = crosses(argil::collide(a, b, to, crossing_test(eps)));
  if (swept && !end_crosses) ++tally.passed_through;
  const double travel = (to.p - from.p).norm();
  const int samples = std::max(1, static_cast<int>(std::ceil(travel / (0.25 * eps))));
  bool sampled_crossing = false, sampled_near = false;
  // The crossing's point on b (its uv_b) passes within eps of it on the
  // way (a point anywhere else on b's leaf need not).
  const Eigen::Vector3d on_b = crossing != nullptr
                                   ? argil::evaluate(patch, crossing->uv_b[0], crossing->uv_b[1])
                                   : Eigen::Vector3d::Zero();
  double b_point_gap = std::numeric_limits<double>::infinity();
  const CollisionRequest near{.tolerance = 3.0 * eps,
                              .max_contacts = 1,
                              .refine = false,
                              .compute_depth = false,
                              .curves = false};
  for (int k = 1; k <= samples && !(sampled_crossing && sampled_near); ++k) {
    const Pose at = argil::interpolate(from, to, static_cast<double>(k) / samples);
    if (!sampled_crossing) sampled_crossing = crosses(argil::collide(a, b, at, crossing_test(eps)));
    if (swept && !sampled_near) sampled_near = !argil::collide(a, b, at, near).contacts.empty();
  }
  for (int k = 0; swept && k <= samples; ++k) {
    const Pose at = argil::interpolate(from, to, static_cast<double>(k) / samples);
    b_point_gap = std::min(b_point_gap, (argil::apply(at, on_b) - crossing->point).norm());
  }
  if (sampled_crossing) CHECK(swept);  // no crossing missed
  if (swept) CHECK(sampled_near);      // none reported far from the motion
  if (swept) CHECK(b_point_gap <= eps);
}

}  // namespace

TEST_CASE(
    "random swept graph patches: every crossing of a dense sampling of the motion is found, and "
    "every reported one has a sampled pose within 3 eps, and b's point at its uv_b passes within "
    "eps",
    "[collision][swept]") {
  std::mt19937_64 rng(415);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double eps = 0.3;
  SweptTally tally;
  for (int trial = 0; trial < 40; ++trial) {
    CAPTURE(trial);
    const BSplineSurface surface = argil::test::graph_surface(rng, 100.0, 8.0, 0.0, 4, 3);
    const BSplineSurface patch = centred_patch(rng, 1.0);
    const argil::SurfaceHierarchy a = argil::test::hierarchy_for(surface);
    const argil::SurfaceHierarchy b = argil::test::hierarchy_for(patch);
    // Straight through (trial % 3 == 0), or anywhere; turning up to 0.2 rad
    // on every other trial (translation only on the rest).
    const Eigen::Vector3d start{20.0 + 60.0 * unit(rng), 20.0 + 60.0 * unit(rng),
                                trial % 3 == 0 ? 12.0 : -14.0 + 28.0 * unit(rng)};
    const Eigen::Vector3d travel{-10.0 + 20.0 * unit(rng), -10.0 + 20.0 * unit(rng),
                                 trial % 3 == 0 ? -24.0 : -14.0 + 28.0 * unit(rng)};
    const Eigen::Vector3d axis =
        Eigen::Vector3d(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5).normalized();
    const Eigen::Quaterniond R0(Eigen::AngleAxisd(0.5 * unit(rng), axis));
    const double angle = trial % 2 == 0 ? 0.0 : 0.2 * unit(rng);
    const Eigen::Quaterniond R1 = Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis)) * R0;
    check_against_sampling(a, b, patch, {R0, start}, {R1, start + travel}, eps, tally);
  }
  CAPTURE(tally.clear_runs, tally.swept_crossings, tally.passed_through);
  // The cases exercise what they test: clear starts, crossings, and crossings
  // that neither end shows.
  CHECK(tally.clear_runs >= 30);
  CHECK(tally.swept_crossings >= 10);
  CHECK(tally.passed_through >= 5);
}

TEST_CASE(
    "random graph patches sliding along a wavy surface just above it: every crossing a dense "
    "sampling finds is found",
    "[collision][swept]") {
  // The swept bounds keep the translation apart from the turn (a tool sliding
  // along a surface stays as far from it as at rest): these motions run
  // nearly along the surface, a few eps above it at the start, so the way
  // clips crests that neither end reaches.
  std::mt19937_64 rng(2811);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double eps = 0.1;
  SweptTally tally;
  for (int trial = 0; trial < 60; ++trial) {
    CAPTURE(trial);
    const BSplineSurface surface = argil::test::graph_surface(rng, 40.0, 5.0, 0.0, 4, 3);
    const BSplineSurface patch = centred_patch(rng, 0.3);
    const argil::SurfaceHierarchy a = argil::test::hierarchy_for(surface);
    const argil::SurfaceHierarchy b = argil::test::hierarchy_for(patch);
    const Eigen::Quaterniond R0(Eigen::AngleAxisd(
        0.1 * unit(rng),
        Eigen::Vector3d(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5).normalized()));
    // Both ends lowered from above in eps steps to the last pose clear by
    // more than eps: the line between them runs through the crests between
    // and over the troughs.
    const double angle = trial % 2 == 0 ? 0.0 : 0.02 * unit(rng);
    const Eigen::Quaterniond R1 =
        Eigen::Quaterniond(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ())) * R0;
    const CollisionRequest touch{.tolerance = eps,
                                 .max_contacts = 1,
                                 .refine = false,
                                 .compute_depth = false,
                                 .curves = false};
    const auto lowered = [&](const Eigen::Quaterniond& R, Eigen::Vector3d p) {
      p.z() = 12.0;
      while (p.z() > -12.0 &&
             argil::collide(a, b, Pose{R, p - Eigen::Vector3d(0, 0, eps)}, touch).contacts.empty())
        p.z() -= eps;
      return p;
    };
    const Eigen::Vector3d start =
        lowered(R0, {10.0 + 20.0 * unit(rng), 10.0 + 20.0 * unit(rng), 0});
    const double heading = 2.0 * M_PI * unit(rng), length = 3.0 + 9.0 * unit(rng);
    const Eigen::Vector3d end =
        lowered(R1, start + length * Eigen::Vector3d(std::cos(heading), std::sin(heading), 0.0));
    const Eigen::Vector3d travel = end - start;
    check_against_sampling(a, b, patch, {R0, start}, {R1, start + travel}, eps, tally);
  }
  CAPTURE(tally.clear_runs, tally.swept_crossings, tally.passed_through);
  CHECK(tally.clear_runs >= 50);
  CHECK(tally.passed_through >= 6);
}
