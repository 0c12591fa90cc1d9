// What a press does to the shape across knot lines and resolutions
// (docs/deformation.md, Testing): a G1 join of two pieces that meet C0 stays
// G1, a real crease keeps its angle, and the same press on a face and on its
// exact 2x and 4x knot refinements gives the same dent and force.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <vector>

#include "argil/core.hpp"
#include "support/random_surface.hpp"
#include "support/sphere_press.hpp"
#include "support/test_plates.hpp"
#include "support/uniform_refinement.hpp"

namespace {

using argil::BSplineSurface;
using argil::Direction;

/// An extruded profile along v: two cubic pieces joined C0 at v = 0.5,
/// extruded 20 mm along u (degree 2, 5 poles). `kink` [deg] is the angle the
/// second piece's tangent turns from the first's at the join: 0 gives a G1
/// join (the poles either side collinear at unequal distances, so not C1).
BSplineSurface two_pieces(double kink_degrees) {
  BSplineSurface s;
  s.degree = {2, 3};
  s.knots = {argil::test::piece_knots(2, 3, 1), argil::test::piece_knots(3, 2, 3)};
  // Profile in (y, z): a rising arc, the join at Q3, then the second piece.
  const double kink = kink_degrees * M_PI / 180.0;
  const Eigen::Vector2d q3(10.0, 2.0);
  const Eigen::Vector2d t_in = Eigen::Vector2d(1.0, 0.25).normalized();
  const Eigen::Vector2d t_out(std::cos(kink) * t_in.x() - std::sin(kink) * t_in.y(),
                              std::sin(kink) * t_in.x() + std::cos(kink) * t_in.y());
  const std::vector<Eigen::Vector2d> q = {{0.0, 0.0},
                                          {3.5, 0.3},
                                          q3 - 3.0 * t_in,
                                          q3,
                                          q3 + 4.5 * t_out,
                                          q3 + 7.0 * t_out + Eigen::Vector2d(0, -0.4),
                                          q3 + 10.0 * t_out + Eigen::Vector2d(0, -1.0)};
  const int nu = s.count(Direction::u);
  s.control_points.resize(nu * 7, 3);
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < 7; ++j)
      s.control_points.row(s.pole_index(i, j)) << 20.0 * i / (nu - 1), q[j].x(), q[j].y();
  return s;
}

/// Largest angle [rad] between the normals either side of the knot line v = 0.5.
double largest_kink(const BSplineSurface& s) {
  double out = 0.0;
  for (int k = 0; k <= 40; ++k) {
    const double u = k / 40.0;
    const Eigen::Vector3d a = argil::unit_normal(s, u, 0.5 - 1e-12);
    const Eigen::Vector3d b = argil::unit_normal(s, u, 0.5 + 1e-12);
    out = std::max(out, std::atan2(a.cross(b).norm(), a.dot(b)));
  }
  return out;
}

/// Clay as preset (yield 0.02 mm: a press flows plastically) and purely elastic.
struct NamedMaterial {
  const char* name;
  argil::Material material;
};
std::vector<NamedMaterial> clays() {
  argil::Material elastic = *argil::material_preset("clay");
  elastic.yield = std::numeric_limits<double>::infinity();
  return {{"clay", *argil::material_preset("clay")}, {"elastic clay", elastic}};
}

argil::test::SpherePress press_at(const Eigen::Vector2d& uv, double radius, double depth,
                                  const argil::Material& material) {
  argil::test::SpherePress p;
  p.uv = uv;
  p.radius = radius;
  p.depth = depth;
  p.press_time = 0.3;
  p.release_time = 0.1;
  p.material = material;
  p.samples = 61;
  return p;
}

BSplineSurface after(const BSplineSurface& s, const argil::ControlNet& points) {
  BSplineSurface out = s;
  out.control_points = points;
  return out;
}

/// The same press on `s` and on its 2x and 4x refinements: dent and peak force within 5%.
void check_resolution(const BSplineSurface& s, const Eigen::Vector2d& uv, double radius,
                      double depth) {
  for (const NamedMaterial& m : clays()) {
    CAPTURE(m.name);
    const argil::test::SpherePress p = press_at(uv, radius, depth, m.material);
    const argil::test::PressOutcome base = argil::test::press_sphere(s, p);
    INFO(base.error);
    REQUIRE(base.error.empty());
    REQUIRE(base.dent > 0.0);
    for (const int times : {1, 2}) {
      const BSplineSurface r = argil::test::halved_spans(s, times);
      const argil::test::PressOutcome fine = argil::test::press_sphere(r, p);
      INFO(fine.error);
      REQUIRE(fine.error.empty());
      CAPTURE(times, r.count(Direction::u), r.count(Direction::v), base.dent, fine.dent,
              base.peak_force, fine.peak_force);
      CHECK(std::abs(fine.dent - base.dent) <= 0.05 * base.dent);
      CHECK(std::abs(fine.peak_force - base.peak_force) <= 0.05 * base.peak_force);
    }
  }
}

}  // namespace

/// Presses a G1 join of two C0 pieces on and near the line with `m`: the
/// kink it leaves is at most 5% of how far the dent turns the normals.
void check_g1_join(const NamedMaterial& m) {
  const BSplineSurface s = two_pieces(0.0);
  REQUIRE(argil::validate(s).ok());
  REQUIRE(largest_kink(s) < 1e-9);  // G1 to rounding
  // Not C1: the cross derivatives either side differ in length.
  const argil::SurfaceDerivatives a = argil::evaluate_derivatives(s, 0.5, 0.5 - 1e-12, 1);
  const argil::SurfaceDerivatives b = argil::evaluate_derivatives(s, 0.5, 0.5 + 1e-12, 1);
  REQUIRE((a.dv - b.dv).norm() > 0.1 * a.dv.norm());
  for (const double v : {0.5, 0.52, 0.46}) {
    CAPTURE(m.name, v);
    const argil::test::SpherePress p = press_at({0.45, v}, 2.0, 0.8, m.material);
    const argil::test::PressOutcome r = argil::test::press_sphere(s, p);
    INFO(r.error);
    REQUIRE(r.error.empty());
    REQUIRE(r.finite);
    const double kink = largest_kink(after(s, r.pressed));
    // A join that stays G1 kinks by a small fraction of how far the dent
    // itself turns the normals: 5%.
    CAPTURE(kink, r.normal_turn, r.dent);
    REQUIRE(r.normal_turn > 0.0);
    CHECK(kink <= 0.05 * r.normal_turn);
  }
}

TEST_CASE("a G1 join of two C0 pieces stays G1 under a plastic press on and near the line",
          "[deformation][joins]") {
  // Plastic flow moves the rest poles of each row across the join together
  // (measured: kink 0.4 to 0.7% of the normal turn; 120 to 180% before).
  check_g1_join(clays()[0]);
}

TEST_CASE("a G1 join of two C0 pieces stays G1 under an elastic press on and near the line",
          "[deformation][joins]") {
  // The pole on the join moves with its row's neighbours (a tie, not a
  // penalty): measured kink below 1e-6 of the normal turn (10 to 15% with
  // the joint penalty alone).
  check_g1_join(clays()[1]);
}

// Known gap, kept visible: [!shouldfail] passes while the model misses this
// target and fails (asking for the tag to go) once it meets it. See
// docs/deformation.md, Limits.
TEST_CASE("a crease keeps its angle under a press on and near it",
          "[deformation][joins][!shouldfail]") {
  const BSplineSurface s = two_pieces(35.0);
  REQUIRE(argil::validate(s).ok());
  const double crease = largest_kink(s);
  REQUIRE(crease == Approx(35.0 * M_PI / 180.0).epsilon(1e-9));
  for (const NamedMaterial& m : clays())
    for (const double v : {0.5, 0.52, 0.46}) {
      CAPTURE(m.name, v);
      const argil::test::SpherePress p = press_at({0.45, v}, 2.0, 0.8, m.material);
      const argil::test::PressOutcome r = argil::test::press_sphere(s, p);
      INFO(r.error);
      REQUIRE(r.error.empty());
      REQUIRE(r.finite);
      // The kink angle along the line, at every sample, changes by a small
      // fraction (5%) of how far the dent turns the normals.
      const BSplineSurface pressed = after(s, r.pressed);
      double change = 0.0;
      for (int k = 0; k <= 40; ++k) {
        const double u = k / 40.0;
        const auto angle = [&](const BSplineSurface& f) {
          const Eigen::Vector3d n0 = argil::unit_normal(f, u, 0.5 - 1e-12);
          const Eigen::Vector3d n1 = argil::unit_normal(f, u, 0.5 + 1e-12);
          return std::atan2(n0.cross(n1).norm(), n0.dot(n1));
        };
        change = std::max(change, std::abs(angle(pressed) - angle(s)));
      }
      CAPTURE(change, r.normal_turn, r.dent);
      REQUIRE(r.normal_turn > 0.0);
      CHECK(change <= 0.05 * r.normal_turn);
    }
}

// A 2 mm sphere pressed 0.5 mm into clay rests on a disc about 1.9 mm across
// (its radius at 0.45 N); the bending length of clay is 2.8 mm. A net with
// 1 mm spans resolves that; the same press on its refinements agrees.
TEST_CASE(
    "resolution independence: a flat panel that resolves the press, and its 2x, 4x "
    "refinements",
    "[deformation][resolution][slow]") {
  check_resolution(argil::test::flat_bicubic_panel(20.0, 20), {0.43, 0.56}, 2.0, 0.5);
}

TEST_CASE("resolution independence: the asymmetric surface and its 2x, 4x refinements",
          "[deformation][resolution]") {
  // Scaled to 15 x 7 mm with its spans halved once (1 to 3.4 mm): a net that
  // resolves a 2 mm sphere's press, with every asymmetry of the original.
  BSplineSurface s = argil::test::halved_spans(argil::test::asymmetric_surface(), 1);
  s.control_points *= 0.25;
  const Eigen::Vector2d uv(0.55, 0.7);  // inside the domain [0, 1] x [-1, 2]
  check_resolution(s, uv, 2.0, 0.5);
}

// Known gap, kept visible: [!shouldfail] passes while the model misses this
// target and fails (asking for the tag to go) once it meets it. See
// docs/deformation.md, Limits. A net coarser than the press (4 mm spans under
// a 2 mm sphere) cannot take the dent's shape: clay's plastic dent comes out
// 38% deeper than on the refinements, elastic clay's 6% shallower. Refining
// such faces where the tool works is the next step.
TEST_CASE("resolution independence: a panel coarser than the press",
          "[deformation][resolution][!shouldfail]") {
  check_resolution(argil::test::flat_bicubic_panel(20.0, 5), {0.43, 0.56}, 2.0, 0.5);
}

// What a session does with that coarse panel before its first tick
// (refine_region to the default resolution, the sphere's radius): the
// refined panel agrees with its own 2x and 4x refinements within 5%
// (measured: clay dent 4.5%, force 2.4%; elastic clay dent 1.7%).
TEST_CASE("resolution independence: a coarse panel refined to the sphere's radius",
          "[deformation][resolution]") {
  const BSplineSurface coarse = argil::test::flat_bicubic_panel(20.0, 5);
  argil::RefinementGoal goal;
  goal.resolution = 2.0;
  const argil::Result<argil::Refinement> refined =
      argil::refine_region(coarse, {0.0, 1.0, 0.0, 1.0}, goal);
  REQUIRE(refined.ok());
  REQUIRE(refined.value().surface.count(Direction::u) == 13);  // 10 spans of 2 mm
  check_resolution(refined.value().surface, {0.43, 0.56}, 2.0, 0.5);
}
